"""Graph benchmarks: `ros2lite topic list` against a graph of 1000 live endpoints.

The endpoints are liveliness tokens (100 nodes x 10 endpoints) declared by a separate process
(in a peer session, as nodes open) connected to the ros2lite daemon on a free loopback port,
so the measured CLI process pays for exactly what a user's would: start-up, the graph from
the daemon's cache, printing. `topic_list_1000_no_daemon_wall` is the same verb with
`--no-daemon`: connecting and one complete liveliness query instead of the cache.
"""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
import time

from common import (
    cli_env,
    environment,
    free_port,
    import_click_wall,
    ready_child,
    report,
    wall,
)

NODES = 100
ENDPOINTS_PER_NODE = 10
STRING_HASH = 'RIHS01_df668c740482bbd48fb39d76a70dfd4bd59db1288021743503259e948f6b1a18'

# Runs in the child: a node's session declaring the tokens; prints "ready".
_GRAPH_CHILD = f'''
import sys
from ros2lite.transport.config import node_session_mode
from ros2lite.transport.open import open_session
from ros2lite.transport.keys import EntityKind, endpoint_token, node_token
from ros2lite.qos import QoSProfile

endpoint, domain = sys.argv[1], int(sys.argv[2])
session = open_session(endpoint, mode=node_session_mode(endpoint), env={{}})  # as nodes do
zid = str(session.info.zid())
lv = session.liveliness()
tokens = []
qos = QoSProfile(depth=10)
half = {ENDPOINTS_PER_NODE} // 2
for n in range({NODES}):
    nid = n * ({ENDPOINTS_PER_NODE} + 1)
    name = f'node_{{n:03d}}'
    tokens.append(lv.declare_token(node_token(domain, zid, nid, '/bench', name)))
    for i in range({ENDPOINTS_PER_NODE}):
        if i < half:
            kind, topic = EntityKind.PUBLISHER, f'/bench/t_{{n:03d}}_{{i}}'
        else:
            peer = (n + 1) % {NODES}
            kind, topic = EntityKind.SUBSCRIPTION, f'/bench/t_{{peer:03d}}_{{i - half}}'
        tokens.append(lv.declare_token(endpoint_token(
            domain, zid, nid, nid + 1 + i, kind, '/bench', name, topic, 'std_msgs/msg/String',
            '{STRING_HASH}', qos)))
print('ready', flush=True)
sys.stdin.read()
'''


def bench_topic_list() -> None:
    endpoint = f'tcp/127.0.0.1:{free_port()}'
    domain = '217'
    with tempfile.TemporaryDirectory() as runtime:
        env = cli_env(endpoint, domain, runtime)
        exe = os.path.join(os.path.dirname(sys.executable), 'ros2lite')
        subprocess.run([exe, 'daemon', 'start'], env=env, check=True, capture_output=True)
        try:
            with ready_child(_GRAPH_CHILD, endpoint, domain, env=env):
                cmd = [exe, 'topic', 'list']
                # sanity: the CLI sees every topic before we time it
                expected = NODES * ENDPOINTS_PER_NODE // 2
                deadline = time.monotonic() + 10
                while True:
                    out = subprocess.run(cmd, env=env, capture_output=True, text=True).stdout
                    if len(out.splitlines()) == expected or time.monotonic() > deadline:
                        break
                    time.sleep(0.05)
                assert len(out.splitlines()) == expected, f'{len(out.splitlines())} topics'
                direct = [*cmd, '--no-daemon']
                out = subprocess.run(direct, env=env, capture_output=True, text=True).stdout
                assert len(out.splitlines()) == expected, f'{len(out.splitlines())} topics'
                with environment(env):  # wall() runs commands with this process' environment
                    ours = wall(cmd, runs=9)
                    no_daemon = wall(direct, runs=9)
                    base = import_click_wall()
        finally:
            subprocess.run([exe, 'daemon', 'stop'], env=env, capture_output=True)
    report('topic_list_1000_wall', ours * 1000, 'ms', ours / base)
    report('topic_list_1000_no_daemon_wall', no_daemon * 1000, 'ms', no_daemon / base)


BENCHES = {'topic_list_1000': bench_topic_list}
