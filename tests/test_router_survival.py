"""Nodes outlive their router: peers keep talking while the daemon is stopped, discovery is
back within a second of its return, nothing stale survives, and a node started with no router
starts the daemon (or, told not to, runs without one and says so once)."""

from __future__ import annotations

import contextlib
import os
import random
import signal
import subprocess
import sys
import threading
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from ros2lite import daemon
from tests.cli.conftest import run_process
from tests.spinning import free_port, wait_until

TALKER = """
import sys, time
import ros2lite
from ros2lite.interfaces import get_interface
String = get_interface('std_msgs/msg/String')
ros2lite.init([])
node = ros2lite.Node(sys.argv[1])
pub = node.create_publisher(String, '/survive', 10)
print('ready', flush=True)
i = 0
try:
    while True:
        pub.publish(String(data=str(i)))
        i += 1
        time.sleep(0.02)
except KeyboardInterrupt:
    pass
"""

LISTENER = """
import sys
import ros2lite
from ros2lite.interfaces import get_interface
String = get_interface('std_msgs/msg/String')
ros2lite.init([])
node = ros2lite.Node(sys.argv[1])
node.create_subscription(String, '/survive', lambda m: print(m.data, flush=True), 10)
print('ready', flush=True)
try:
    ros2lite.spin(node)
except KeyboardInterrupt:
    pass
"""

IDLE = """
import sys, time
import ros2lite
ros2lite.init([])
node = ros2lite.Node(sys.argv[1])
print('ready', flush=True)
try:
    time.sleep(120)
except KeyboardInterrupt:
    pass
"""


class Node:
    """A node process whose stdout lines are collected by a thread as they arrive."""

    def __init__(self, code: str, name: str, env: dict[str, str]) -> None:
        self.proc = subprocess.Popen(
            [sys.executable, '-c', code, name],
            env=env,
            text=True,
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
        )
        self.lines: list[str] = []
        self._reader = threading.Thread(target=self._read, daemon=True)
        self._reader.start()

    def _read(self) -> None:
        assert self.proc.stdout is not None
        for line in self.proc.stdout:
            self.lines.append(line.strip())

    def ready(self) -> bool:
        return 'ready' in self.lines

    def numbers(self) -> list[int]:
        return [int(n) for n in self.lines if n.isdigit()]

    def stop(self) -> str:
        """Stop it (SIGINT, then SIGKILL) and return its stderr."""
        if self.proc.poll() is None:
            self.proc.send_signal(signal.SIGINT)
        try:
            _out, err = self.proc.communicate(timeout=5)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            _out, err = self.proc.communicate()
        return err or ''


@pytest.fixture
def private(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Iterator[dict[str, str]]:
    """A free endpoint, runtime dir and domain (here and for children); the daemon a test
    leaves behind is stopped."""
    endpoint = f'tcp/127.0.0.1:{free_port()}'
    env = {
        'ROS2LITE_ROUTER': endpoint,
        'XDG_RUNTIME_DIR': str(tmp_path),
        'ROS_DOMAIN_ID': str(random.randint(100, 232)),
    }
    for key, value in env.items():
        monkeypatch.setenv(key, value)
    for var in (
        'ZENOH_CONFIG_OVERRIDE',
        'ZENOH_SESSION_CONFIG_URI',
        'ZENOH_ROUTER_CONFIG_URI',
        'ZENOH_ROUTER_CHECK_ATTEMPTS',
        'ROS2LITE_NO_DAEMON',
    ):
        monkeypatch.delenv(var, raising=False)
    yield env
    info = daemon.status(endpoint).info
    if info is not None:
        with contextlib.suppress(Exception):
            daemon.stop(endpoint, timeout=2)
        with contextlib.suppress(OSError):
            os.kill(info.pid, signal.SIGKILL)


def node_names(endpoint: str) -> set[str]:
    """Node names as a CLI verb sees them: one client session asking the router."""
    from ros2lite.graph import node_names_and_namespaces, snapshot
    from ros2lite.transport.config import domain_id
    from ros2lite.transport.open import open_session

    session = open_session(endpoint)
    try:
        entities = snapshot(session, domain_id())
    finally:
        session.close()
    return {ns.rstrip('/') + '/' + name for name, ns in node_names_and_namespaces(entities)}


def test_talk_through_a_router_outage_and_rediscover_quickly(private: dict[str, str]) -> None:
    endpoint = private['ROS2LITE_ROUTER']
    # nodes here must not restart the daemon themselves while it is down
    env = {**os.environ, **private, 'ROS2LITE_NO_DAEMON': '1'}
    daemon.start(endpoint)
    nodes: list[Node] = []
    try:
        listener = Node(LISTENER, 'listener', env)
        doomed = Node(IDLE, 'doomed', env)
        talker = Node(TALKER, 'talker', env)
        nodes += [listener, doomed, talker]
        wait_until(lambda: len(listener.numbers()) >= 10, timeout=20)

        stop = run_process('daemon', 'stop', env=private)
        assert stop.code == 0, stop.err
        assert stop.out.splitlines()[:2] == [
            'The daemon has been stopped',
            '3 sessions were connected to it (nodes: /doomed, /listener, /talker)',
        ]
        assert '3 peer sessions keep exchanging data' in stop.out
        heard_at_stop = len(listener.numbers())

        # while the router is down: a node dies, another starts, the pair keeps talking
        doomed.proc.kill()
        late = Node(LISTENER, 'late', env)
        nodes.append(late)
        wait_until(late.ready, timeout=20)
        time.sleep(2.0)
        assert len(listener.numbers()) >= heard_at_stop + 25  # 50 Hz for 2 s

        assert daemon.start(endpoint).started
        back = time.monotonic()
        names = wait_until(
            lambda: (n := node_names(endpoint)) and '/late' in n and n, timeout=5, interval=0.01
        )
        assert time.monotonic() - back < 1.0
        assert names == {'/listener', '/talker', '/late'}  # /doomed is gone
        wait_until(lambda: len(late.numbers()) >= 3, timeout=5)  # introduced to the talker
    finally:
        errors = [node.stop() for node in nodes]
    heard = listener.numbers()
    assert heard == list(range(heard[0], heard[-1] + 1))  # no message lost, none repeated
    assert not any('Traceback' in err for err in errors), errors
    assert 'no Zenoh router answers at' in errors[-1] and 'running without one' in errors[-1]


def test_run_with_no_router_starts_the_daemon(private: dict[str, str]) -> None:
    endpoint = private['ROS2LITE_ROUTER']
    assert not daemon.status(endpoint).running
    proc = subprocess.Popen(
        [sys.executable, '-m', 'ros2lite', 'run', 'demo_nodes_py', 'talker'],
        env={**os.environ, **private},
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    try:
        wait_until(lambda: daemon.status(endpoint).ours, timeout=20)
        # typed, so echo waits for the talker even if its publisher is not in the graph yet
        heard = subprocess.run(
            [
                sys.executable,
                '-m',
                'ros2lite',
                'topic',
                'echo',
                '--once',
                '/chatter',
                'std_msgs/msg/String',
            ],
            env={**os.environ, **private},
            timeout=30,
            capture_output=True,
            text=True,
        )
        assert heard.stdout.startswith("data: 'Hello World: ")
    finally:
        proc.send_signal(signal.SIGINT)
        _out, err = proc.communicate(timeout=10)
    assert proc.returncode == 0
    assert 'Traceback' not in err
    assert f'no Zenoh router answered at {endpoint}: started the ros2lite daemon' in err


@pytest.mark.parametrize(
    'attempts, waits, lines',
    [
        (None, 0.0, ['running without one']),
        ('2', 1.0, ['waiting for up to 2 s', 'running without one']),
        ('-1', 0.0, []),
    ],
)
def test_node_with_no_router_and_no_daemon(
    private: dict[str, str],
    capfd: Any,
    monkeypatch: pytest.MonkeyPatch,
    attempts: str | None,
    waits: float,
    lines: list[str],
) -> None:
    """rmw_zenoh's behaviour: ZENOH_ROUTER_CHECK_ATTEMPTS checks, one clear line, go on."""
    from ros2lite.context import Context

    if attempts is None:
        monkeypatch.setenv('ROS2LITE_NO_DAEMON', '1')
    else:
        monkeypatch.setenv('ZENOH_ROUTER_CHECK_ATTEMPTS', attempts)
    ctx = Context()
    start = time.monotonic()
    ctx.init([])
    try:
        elapsed = time.monotonic() - start
        assert ctx.ok()
        assert waits <= elapsed < waits + 3.0
    finally:
        ctx.shutdown()
    err = capfd.readouterr().err
    assert err.count('\n') == len(lines), err
    for line, text in zip(err.splitlines(), lines, strict=True):
        assert line.startswith('[WARN]') and text in line
    assert not daemon.status(private['ROS2LITE_ROUTER']).running


def test_rmw_zenoh_peer_keeps_hearing_a_node_without_router(private: dict[str, str]) -> None:
    """A session configured as rmw_zenoh's default session config (peer, loopback listener,
    gossip through the router, written out literally here) and a ros2lite node talk directly,
    so the data keeps flowing while the router is stopped."""
    import zenoh

    from ros2lite.context import Context
    from ros2lite.interfaces import get_interface
    from ros2lite.node import Node as RosNode

    endpoint = private['ROS2LITE_ROUTER']
    daemon.start(endpoint)
    conf = zenoh.Config()
    for key, value in [
        ('mode', '"peer"'),
        ('connect/endpoints', f'["{endpoint}"]'),
        ('listen/endpoints', '["tcp/localhost:0"]'),
        ('scouting/multicast/enabled', 'false'),
        ('scouting/gossip/enabled', 'true'),
        ('scouting/gossip/target', '{router: ["router", "peer"], peer: ["router"]}'),
        ('scouting/gossip/autoconnect', '{router: [], peer: ["router", "peer"]}'),
        (
            'scouting/gossip/autoconnect_strategy',
            '{peer: {to_router: "always", to_peer: "greater-zid"}}',
        ),
        ('timestamping/enabled', 'true'),
    ]:
        conf.insert_json5(key, value)
    alien = zenoh.open(conf)
    heard: list[bytes] = []
    key = (
        f"{private['ROS_DOMAIN_ID']}/outage_chatter/std_msgs::msg::dds_::String_/"
        'RIHS01_df668c740482bbd48fb39d76a70dfd4bd59db1288021743503259e948f6b1a18'
    )
    sub = alien.declare_subscriber(key, lambda s: heard.append(s.payload.to_bytes()))
    ctx = Context().init([])
    stop = threading.Event()
    try:
        String = get_interface('std_msgs/msg/String')
        pub = RosNode('outage_node', context=ctx).create_publisher(String, '/outage_chatter', 10)

        def talk() -> None:
            while not stop.wait(0.02):
                pub.publish(String(data='hi'))

        threading.Thread(target=talk, daemon=True).start()
        wait_until(lambda: len(heard) >= 5, timeout=10)
        assert daemon.stop(endpoint).stopped
        before = len(heard)
        time.sleep(1.0)
        assert len(heard) >= before + 20  # 50 Hz, no router
        assert heard[-1] == b'\x00\x01\x00\x00\x03\x00\x00\x00hi\x00'
    finally:
        stop.set()
        ctx.shutdown()
        sub.undeclare()
        alien.close()
