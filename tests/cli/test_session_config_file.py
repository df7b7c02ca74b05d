"""The CLI's graph verbs with ZENOH_SESSION_CONFIG_URI pointing at a session file like
rmw_zenoh's own default (written here from its documented defaults: peer mode, connect to
the router on localhost, multicast scouting off, gossip on): every run sees the whole graph
(R5-W2 measured 2 runs in 6 before: a peer's view fills only as peer links open)."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest

from tests.cli.conftest import Result
from tests.spinning import wait_until

SESSION = """{
  mode: "peer",
  connect: { endpoints: ["tcp/localhost:%d"] },
  listen: { endpoints: ["tcp/localhost:0"] },
  open: { return_conditions: { connect_scouted: true, declares: true } },
  scouting: {
    multicast: { enabled: false },
    gossip: {
      enabled: true,
      multihop: false,
      target: { router: ["router", "peer"], peer: ["router"] },
      autoconnect: { router: [], peer: ["router", "peer"] },
      autoconnect_strategy: { peer: { to_router: "always", to_peer: "greater-zid" } },
    },
  },
  timestamping: { enabled: true },
  queries_default_timeout: 600000,
}"""

TALKER = """
import ros2lite
from ros2lite.node import Node
from ros2lite.msgs.std_msgs.msg import String
ros2lite.init()
node = Node('cfg_talker')
pub = node.create_publisher(String, 'cfg_chatter', 10)
node.create_timer(0.1, lambda: pub.publish(String(data='hi')))
print('ready', flush=True)
ros2lite.spin(node)
"""


def test_graph_verbs_every_time_with_rmw_zenohs_session_file(
    run: Callable[..., Result],
    processes: Any,
    ros_router: str,
    tmp_path: Path,
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    talker = processes.python(TALKER)
    assert talker.stdout.readline().strip() == 'ready'
    assert wait_until(lambda: '/cfg_talker' in run('node', 'list').out, timeout=10)
    path = tmp_path / 'session.json5'
    path.write_text(SESSION % int(ros_router.rsplit(':', 1)[1]))
    monkeypatch.setenv('ZENOH_SESSION_CONFIG_URI', str(path))
    monkeypatch.delenv('ROS2LITE_ROUTER')  # the file alone says where the router is
    checks = {
        ('node', 'list'): '/cfg_talker\n',
        ('topic', 'info', '/cfg_chatter'): 'Publisher count: 1\n',
        ('service', 'list'): '/cfg_talker/get_parameters\n',
    }
    seen = {verb: 0 for verb in checks}
    for _ in range(10):
        for verb, expected in checks.items():
            result = run(*verb)
            seen[verb] += result.code == 0 and expected in result.out
    echoes = 0
    for _ in range(3):
        result = run('topic', 'echo', '--once', '/cfg_chatter')
        echoes += result.code == 0 and "data: hi" in result.out
    assert seen == {verb: 10 for verb in checks} and echoes == 3, (seen, echoes)
