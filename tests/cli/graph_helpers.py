"""Helpers for the live-graph CLI tests: a private domain per test, a bare Zenoh session that
declares rmw_zenoh liveliness tokens by hand, and a small ros2lite node process.

Hand-made tokens let a test build any graph (services, actions, odd QoS, duplicate names,
other sessions' ids) exactly as an rmw_zenoh peer would announce it, so expected outputs can
be written out in full; node processes check the same verbs against real ros2lite nodes.
"""

from __future__ import annotations

import itertools
import random
import subprocess
from collections.abc import Callable
from typing import Any

import pytest

from ros2lite.qos import DurabilityPolicy, QoSProfile
from ros2lite.transport.keys import EntityKind, endpoint_token, node_token

STRING = 'std_msgs/msg/String'
STRING_HASH = 'RIHS01_df668c740482bbd48fb39d76a70dfd4bd59db1288021743503259e948f6b1a18'

# the session fixture uses domains 100..232; each test here takes its own below that, so
# nothing another test left behind can show up in an exact expected output
_domains = itertools.cycle(range(random.randint(1, 99), 100))


def private_domain(monkeypatch: pytest.MonkeyPatch) -> int:
    """Give this test a ROS_DOMAIN_ID of its own (restored afterwards)."""
    domain = next(_domains)
    monkeypatch.setenv('ROS_DOMAIN_ID', str(domain))
    return domain


def fake_hash(type_name: str) -> str:
    """A well-formed, per-type RIHS01 string (the graph only carries it around)."""
    import hashlib

    return 'RIHS01_' + hashlib.sha256(type_name.encode()).hexdigest()


class FakeNode:
    """One node's tokens in a TokenGraph."""

    def __init__(self, graph: TokenGraph, namespace: str, name: str, zid: str, nid: int) -> None:
        self.graph, self.namespace, self.name, self.zid, self.nid = graph, namespace, name, zid, nid
        self.tokens: dict[str, Any] = {}
        graph.declare(node_token(graph.domain, zid, nid, namespace, name))

    def endpoint(
        self,
        kind: EntityKind,
        topic: str,
        type_name: str,
        qos: QoSProfile | None = None,
        type_hash: str | None = None,
    ) -> str:
        """Declare an MP/MS/SS/SC token; returns its key."""
        key = endpoint_token(
            self.graph.domain,
            self.zid,
            self.nid,
            self.graph.next_id(),
            kind,
            self.namespace,
            self.name,
            topic,
            type_name,
            type_hash or fake_hash(type_name),
            qos or QoSProfile(depth=10),
        )
        self.graph.declare(key)
        return key

    def pub(
        self,
        topic: str,
        type_name: str = STRING,
        qos: QoSProfile | None = None,
        type_hash: str | None = None,
    ) -> str:
        return self.endpoint(EntityKind.PUBLISHER, topic, type_name, qos, type_hash)

    def sub(
        self,
        topic: str,
        type_name: str = STRING,
        qos: QoSProfile | None = None,
        type_hash: str | None = None,
    ) -> str:
        return self.endpoint(EntityKind.SUBSCRIPTION, topic, type_name, qos, type_hash)

    def server(self, service: str, type_name: str) -> str:
        return self.endpoint(EntityKind.SERVICE, service, type_name)

    def client(self, service: str, type_name: str) -> str:
        return self.endpoint(EntityKind.CLIENT, service, type_name)

    def _action(self, action: str, action_type: str, server: bool) -> None:
        """The five entities rcl_action creates for one action server or client."""
        status_qos = QoSProfile(depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL)
        service = self.server if server else self.client
        topic = self.pub if server else self.sub
        service(f'{action}/_action/send_goal', f'{action_type}_SendGoal')
        service(f'{action}/_action/cancel_goal', 'action_msgs/srv/CancelGoal')
        service(f'{action}/_action/get_result', f'{action_type}_GetResult')
        topic(f'{action}/_action/feedback', f'{action_type}_FeedbackMessage')
        topic(f'{action}/_action/status', 'action_msgs/msg/GoalStatusArray', status_qos)

    def action_server(self, action: str, action_type: str) -> None:
        self._action(action, action_type, server=True)

    def action_client(self, action: str, action_type: str) -> None:
        self._action(action, action_type, server=False)


class TokenGraph:
    """A bare Zenoh session (no ros2lite Context) declaring liveliness tokens."""

    def __init__(self, domain: int) -> None:
        from ros2lite.transport.open import open_session

        self.domain = domain
        self.session = open_session()
        self.zid = str(self.session.info.zid())
        self._ids = itertools.count()
        self._tokens: dict[str, Any] = {}

    def next_id(self) -> int:
        return next(self._ids)

    def declare(self, key: str) -> None:
        self._tokens[key] = self.session.liveliness().declare_token(key)

    def undeclare(self, key: str) -> None:
        self._tokens.pop(key).undeclare()

    def node(self, name: str, namespace: str = '/', zid: str | None = None) -> FakeNode:
        """A node; pass another `zid` to make it look like it lives in another process."""
        return FakeNode(self, namespace, name, zid or self.zid, self.next_id())

    def close(self) -> None:
        for token in self._tokens.values():
            token.undeclare()
        self._tokens.clear()
        self.session.close()

    def __enter__(self) -> TokenGraph:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


# A real ros2lite node process: argv = name, namespace, then "pub:TOPIC:TYPE:DEPTH" or
# "sub:TOPIC:TYPE:DEPTH" items. Prints each endpoint's resolved topic and GID, then "ready",
# and runs until stdin closes or it is interrupted.
NODE_SCRIPT = '''
import sys
import ros2lite
from ros2lite.node import Node
ros2lite.init()
node = Node(sys.argv[1], namespace=sys.argv[2])
for item in sys.argv[3:]:
    kind, topic, type_name, depth = item.split(':')
    if kind == 'pub':
        ep = node.create_publisher(type_name, topic, int(depth))
    else:
        ep = node.create_subscription(type_name, topic, lambda m: None, int(depth))
    gid = getattr(ep, 'gid', None)
    print(kind, ep.topic_name, gid.hex() if gid else '-', flush=True)
print('ready', flush=True)
try:
    sys.stdin.read()
except KeyboardInterrupt:
    pass
ros2lite.shutdown()
'''


def start_node(
    processes: Any, name: str, namespace: str, *items: str
) -> tuple[subprocess.Popen[str], dict[str, str]]:
    """Start NODE_SCRIPT; returns the process and {topic: gid hex} once it is ready."""
    import queue
    import threading

    proc = processes.python(NODE_SCRIPT, name, namespace, *items, stdin=subprocess.PIPE)
    lines: queue.SimpleQueue[str] = queue.SimpleQueue()
    out = proc.stdout
    assert out is not None

    def pump() -> None:  # a thread, so a stuck node cannot hang the test on readline()
        try:
            for line in out:
                lines.put(line)
        except (OSError, ValueError):
            pass  # closed by Processes.stop() at teardown
        lines.put('')

    threading.Thread(target=pump, daemon=True).start()
    gids: dict[str, str] = {}
    while True:
        try:
            line = lines.get(timeout=20)
        except queue.Empty:
            break
        if not line:
            break
        if line.strip() == 'ready':
            return proc, gids
        kind, topic, gid = line.split()
        if kind == 'pub':
            gids[topic] = gid
    _, err = processes.stop(proc)
    raise AssertionError(f'node {name} did not get ready: {err}')


def dotted(gid_hex: str) -> str:
    return '.'.join(gid_hex[i : i + 2] for i in range(0, len(gid_hex), 2))


def settle(
    run: Any,
    *args: str,
    expected: str | None = None,
    until: Callable[[str], bool] | None = None,
    timeout: float = 10.0,
) -> Any:
    """Run `ros2lite ARGS` until stdout equals `expected` (or `until(stdout)` holds) or the
    timeout passes, since tokens take a moment to reach the router; returns the last result
    for the test to assert on."""
    import time

    done = until or (lambda out: out == expected)
    deadline = time.monotonic() + timeout
    while True:
        result = run(*args)
        if done(result.out) or time.monotonic() > deadline:
            return result
        time.sleep(0.05)
