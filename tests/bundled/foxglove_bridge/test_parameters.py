"""Parameters through the bridge under a hostile request: one `getParameters` naming 20,000
nodes that do not exist (R5-F1) asks no one, holds no other client's handshake, and leaves
the bridge's memory where it was."""

from __future__ import annotations

import socket
import time
from pathlib import Path
from typing import Any

from tests.bundled.test_foxglove_bridge import client_factory, pytestmark, start_bridge
from tests.spinning import wait_until

__all__ = ['client_factory', 'pytestmark']


def _handshake_seconds(port: int) -> float:
    """How long a WebSocket upgrade to the bridge takes to be answered with 101."""
    started = time.monotonic()
    with socket.create_connection(('127.0.0.1', port), timeout=30) as sock:
        sock.sendall(
            b'GET / HTTP/1.1\r\nHost: 127.0.0.1\r\nUpgrade: websocket\r\n'
            b'Connection: Upgrade\r\nSec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\n'
            b'Sec-WebSocket-Version: 13\r\nSec-WebSocket-Protocol: foxglove.sdk.v1\r\n\r\n'
        )
        answer = b''
        while b'\r\n\r\n' not in answer:
            chunk = sock.recv(4096)
            assert chunk, answer
            answer += chunk
    assert answer.startswith(b'HTTP/1.1 101'), answer
    return time.monotonic() - started


def _rss_mib(pid: int) -> float:
    for line in Path(f'/proc/{pid}/status').read_text().splitlines():
        if line.startswith('VmRSS:'):
            return int(line.split()[1]) / 1024
    raise AssertionError('no VmRSS')


def test_getparameters_of_20000_unknown_nodes_locks_no_one_out(
    processes: Any, client_factory: Any, ros_context: Any
) -> None:
    from ros2lite.node import Node

    processes.cli('run', 'demo_nodes_py', 'talker')
    bridge, port, _ = start_bridge(processes)
    watcher = Node('fox_param_watcher', context=ros_context)
    client = client_factory(port)
    client.expect(lambda e: e['event'] == 'serverInfo')
    # a real node's parameter first: the bridge's parameter path works and is warm
    wait_until(lambda: '/talker' in watcher.get_fully_qualified_node_names(), timeout=20)
    client.send(cmd='getParameters', names=['/talker.use_sim_time'], id='real')
    real = client.expect(lambda e: e['event'] == 'parameterValues' and e.get('id') == 'real')
    assert real['parameters'] == [{'name': '/talker.use_sim_time', 'value': False}]
    before = _rss_mib(bridge.pid)
    services_before = len(watcher.get_service_names_and_types())

    names = [f'/fake{i}.x' for i in range(20_000)]
    for round_ in range(3):
        client.send(cmd='getParameters', names=names, id=f'flood{round_}')
        # another client is answered at once meanwhile (it waited 451 s before)
        assert _handshake_seconds(port) < 1.0
        answer = client.expect(
            lambda e, r=round_: e['event'] == 'parameterValues' and e.get('id') == f'flood{r}',
            timeout=10,
        )
        assert answer['parameters'] == []
    assert _handshake_seconds(port) < 1.0
    # no parameter client per name (each would have been declared before the answer): the
    # graph did not grow, and memory is back where it was
    assert len(watcher.get_service_names_and_types()) <= services_before + 2
    assert _rss_mib(bridge.pid) < before + 30, (before, _rss_mib(bridge.pid))
    assert bridge.poll() is None
