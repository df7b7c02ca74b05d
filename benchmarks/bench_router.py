"""A router outage: what a running talker→listener pair and discovery go through.

A ros2lite daemon on a free loopback port (private runtime dir and domain), a talker node
publishing a counter at 100 Hz (reliable, volatile) and a listener node, each its own process.
After a second of traffic the daemon is stopped for `OUTAGE` s (`daemon.stop`), a third node
starts meanwhile, then the daemon is started again. Measured:

* `router_outage_gap`: the longest silence the listener saw (ms), and `router_outage_lost`:
  counter values it never got;
* `router_restart_discovery`: from calling `daemon.start()` (spawning the router included) until
  a client session (what a CLI verb opens) lists the node started during the outage (ms). In
  client mode that node cannot start at all, so the baseline there is the old listener
  reappearing in the graph. `…_after_ready` counts from the router answering instead.

Nodes run as they do by default (peer sessions); the baseline is the same run with every node
forced to client mode (`ZENOH_CONFIG_OVERRIDE='mode="client"'`, the behaviour before peer nodes),
so each ratio is peer / client measured side by side.
"""

from __future__ import annotations

import contextlib
import itertools
import os
import random
import socket
import subprocess
import sys
import tempfile
import threading
import time
from collections.abc import Iterator
from typing import Any

from common import report

OUTAGE = 5.0

TALKER = '''
import time
import ros2lite
from ros2lite.interfaces import get_interface
String = get_interface('std_msgs/msg/String')
ros2lite.init([])
node = ros2lite.Node('outage_talker')
pub = node.create_publisher(String, '/outage', 100)
print('ready', flush=True)
i = 0
start = time.monotonic()
try:
    while True:
        pub.publish(String(data=str(i)))
        i += 1
        time.sleep(max(0.0, start + i * 0.01 - time.monotonic()))
except KeyboardInterrupt:
    pass
'''

LISTENER = '''
import sys, time
import ros2lite
from ros2lite.interfaces import get_interface
String = get_interface('std_msgs/msg/String')
ros2lite.init([])
node = ros2lite.Node(sys.argv[1])
node.create_subscription(String, '/outage', lambda m: print(m.data, time.monotonic(), flush=True),
                         100)
print('ready', flush=True)
try:
    ros2lite.spin(node)
except KeyboardInterrupt:
    pass
'''


class Proc:
    def __init__(self, code: str, env: dict[str, str], *args: str) -> None:
        self.proc = subprocess.Popen(
            [sys.executable, '-c', code, *args],
            env=env,
            text=True,
            stdout=subprocess.PIPE,
            stderr=subprocess.DEVNULL,
        )
        self.samples: list[tuple[int, float]] = []
        self.ready = threading.Event()
        threading.Thread(target=self._read, daemon=True).start()

    def _read(self) -> None:
        assert self.proc.stdout is not None
        for line in self.proc.stdout:
            parts = line.split()
            if parts == ['ready']:
                self.ready.set()
            elif len(parts) == 2:
                self.samples.append((int(parts[0]), float(parts[1])))

    def stop(self) -> None:
        self.proc.terminate()
        with contextlib.suppress(subprocess.TimeoutExpired):
            self.proc.wait(timeout=5)
        if self.proc.poll() is None:
            self.proc.kill()
            self.proc.wait()


@contextlib.contextmanager
def _environment(env: dict[str, str]) -> Iterator[None]:
    saved = dict(os.environ)
    os.environ.update(env)
    try:
        yield
    finally:
        os.environ.clear()
        os.environ.update(saved)


def _node_names(endpoint: str) -> set[str]:
    from ros2lite.graph import node_names_and_namespaces, snapshot
    from ros2lite.transport.config import domain_id
    from ros2lite.transport.open import open_session

    try:
        session = open_session(endpoint, timeout=0.5)
    except Exception:
        return set()
    try:
        return {n for n, _ in node_names_and_namespaces(snapshot(session, domain_id()))}
    finally:
        session.close()


def _wait(predicate: Any, timeout: float) -> bool:
    deadline = time.monotonic() + timeout
    while not predicate():
        if time.monotonic() > deadline:
            return False
        time.sleep(0.005)
    return True


def outage(mode: str | None) -> tuple[float, int, float, float]:
    """One run; returns (longest gap s, lost messages, rediscovery s from the start call and
    from the router answering)."""
    from ros2lite import daemon

    with socket.socket() as sock:
        sock.bind(('127.0.0.1', 0))
        endpoint = f'tcp/127.0.0.1:{sock.getsockname()[1]}'
    runtime = tempfile.mkdtemp()
    env = {
        'ROS2LITE_ROUTER': endpoint,
        'XDG_RUNTIME_DIR': runtime,
        'ROS2LITE_NO_DAEMON': '1',
        'ROS_DOMAIN_ID': str(random.randint(100, 232)),
    }
    with _environment(env):
        for var in ('ZENOH_SESSION_CONFIG_URI', 'ZENOH_ROUTER_CONFIG_URI', 'ZENOH_CONFIG_OVERRIDE'):
            os.environ.pop(var, None)
        child_env = dict(os.environ)
        if mode:  # the nodes only: the override would apply to the router too
            child_env['ZENOH_CONFIG_OVERRIDE'] = f'mode="{mode}"'

        daemon.start(endpoint)
        procs: list[Proc] = []
        try:
            listener = Proc(LISTENER, child_env, 'outage_listener')
            talker = Proc(TALKER, child_env)
            procs += [listener, talker]
            if not _wait(lambda: len(listener.samples) > 100, 20):
                raise RuntimeError('listener never heard the talker')
            daemon.stop(endpoint)
            late = Proc(LISTENER, child_env, 'outage_late') if mode != 'client' else None
            if late:
                procs.append(late)
            time.sleep(OUTAGE)
            watched = 'outage_late' if late else 'outage_listener'
            back = time.monotonic()  # includes spawning the router: what a user waits for
            daemon.start(endpoint)
            answering = time.monotonic()
            _wait(lambda: watched in _node_names(endpoint), 30)
            rediscovery = time.monotonic() - back
            after_ready = time.monotonic() - answering
            heard_before = len(listener.samples)
            _wait(lambda: len(listener.samples) > heard_before + 50, 30)
        finally:
            for proc in procs:
                proc.stop()
            daemon.stop(endpoint)
    times = [t for _, t in listener.samples]
    seqs = [s for s, _ in listener.samples]
    gap = max(b - a for a, b in itertools.pairwise(times))
    lost = (seqs[-1] - seqs[0] + 1) - len(set(seqs))
    return gap, lost, rediscovery, after_ready


def bench_router_outage() -> None:
    peer = outage(None)
    client = outage('client')
    report('router_outage_gap', peer[0] * 1000, 'ms', peer[0] / client[0])
    report('router_outage_gap_client_mode', client[0] * 1000, 'ms', 1.0)
    report('router_outage_lost', peer[1], 'msgs', peer[1] / max(client[1], 1))
    report('router_outage_lost_client_mode', client[1], 'msgs', 1.0)
    report('router_restart_discovery', peer[2] * 1000, 'ms', peer[2] / client[2])
    report('router_restart_discovery_client_mode', client[2] * 1000, 'ms', 1.0)
    report('router_restart_discovery_after_ready', peer[3] * 1000, 'ms', peer[3] / client[3])
    report('router_restart_discovery_after_ready_client_mode', client[3] * 1000, 'ms', 1.0)


BENCHES = {'router_outage': bench_router_outage}
