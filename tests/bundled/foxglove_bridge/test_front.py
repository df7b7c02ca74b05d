"""The bridge's front: a client offering only the protocol's older name
(`foxglove.websocket.v1`, PlotJuggler's and `@foxglove/ws-protocol`'s default) is served
like one offering the current name; the handshake is bounded and loopback is the default."""

from __future__ import annotations

import re
import socket
import time
from typing import Any

from ros2lite.bundled.foxglove_bridge.front import (
    NEW_NAME,
    OLD_NAME,
    SubprotocolFront,
    offered,
    rewrite_answer,
    rewrite_request,
)
from ros2lite.bundled.foxglove_bridge.state import Settings
from tests.bundled.test_foxglove_bridge import client_factory, pytestmark, start_bridge
from tests.spinning import wait_until

__all__ = ['client_factory', 'pytestmark']

_SEEN_AS = r'Client 127\.0\.0\.1:\d+ connected \(the server sees it as 127\.0\.0\.1:\d+\)'
HEAD = (
    b'GET / HTTP/1.1\r\nHost: 127.0.0.1\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n'
    b'Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\nSec-WebSocket-Version: 13\r\n'
)


def test_only_the_old_name_is_rewritten() -> None:
    old = HEAD + b'sec-websocket-protocol: ' + OLD_NAME.encode() + b'\r\n\r\n'
    head, rewrite = rewrite_request(old)
    assert rewrite and offered(head) == [NEW_NAME]
    assert head.endswith(b'\r\n\r\n') and head.count(b'\r\n\r\n') == 1
    assert head.startswith(HEAD)
    # both offered, the new one in a second header line: the SDK picks it, nothing changes
    both = HEAD + f'Sec-WebSocket-Protocol: {OLD_NAME}\r\n'.encode()
    both += f'Sec-WebSocket-Protocol: {NEW_NAME}\r\n\r\n'.encode()
    assert rewrite_request(both) == (both, False)
    neither = HEAD + b'Sec-WebSocket-Protocol: chat\r\n\r\n'
    assert rewrite_request(neither) == (neither, False)
    answer = b'HTTP/1.1 101 Switching Protocols\r\nSec-WebSocket-Protocol: foxglove.sdk.v1\r\n\r\n'
    assert offered(b'x\r\n' + rewrite_answer(answer).split(b'\r\n', 1)[1]) == [OLD_NAME]


def test_the_front_binds_loopback_by_default() -> None:
    assert Settings().address == '127.0.0.1'
    front = SubprotocolFront(Settings().address, 0, 1)
    try:
        assert front.address[0] == '127.0.0.1'
    finally:
        front.close()


def test_old_name_connects_subscribes_and_decodes_a_talker(
    processes: Any, client_factory: Any
) -> None:
    processes.cli('run', 'demo_nodes_py', 'talker')
    _, port, log = start_bridge(processes)
    # a half-sent handshake (slowloris) holds no one else up: one thread serves them all
    lazy = socket.create_connection(('127.0.0.1', port))
    lazy.sendall(HEAD)
    legacy = client_factory(port, OLD_NAME)
    opened = legacy.expect(lambda e: e['event'] in ('open', 'rejected'))
    assert opened == {'event': 'open', 'protocol': OLD_NAME}
    info = legacy.expect(lambda e: e['event'] == 'serverInfo')['info']
    assert 'parameters' in info['capabilities']
    assert legacy.channels({'/chatter'})['/chatter']['parsed']
    legacy.send(cmd='subscribe', topic='/chatter', decode=3)
    numbers = []
    for _ in range(3):
        data = legacy.message('/chatter')['data']
        assert data.startswith('Hello World: '), data
        numbers.append(int(data.rsplit(' ', 1)[1]))
    assert numbers == sorted(numbers) and len(set(numbers)) == 3
    # the current name is still answered as itself, alongside
    current = client_factory(port, NEW_NAME)
    assert current.expect(lambda e: e['event'] in ('open', 'rejected'))['protocol'] == NEW_NAME
    lazy.close()
    # the SDK sees the front's address: the log says who stands behind it
    wait_until(lambda: any(re.search(_SEEN_AS, line) for line in log), timeout=20)


def test_an_unfinished_handshake_is_ended(processes: Any) -> None:
    front = SubprotocolFront('127.0.0.1', 0, 1)
    front.start()
    try:
        lazy = socket.create_connection(('127.0.0.1', front.port))
        lazy.sendall(HEAD)
        lazy.settimeout(20)
        started = time.monotonic()
        assert lazy.recv(10) == b''  # ended by the front (10 s for a handshake)
        assert time.monotonic() - started < 15
        # a head longer than the bound is refused at once
        big = socket.create_connection(('127.0.0.1', front.port))
        big.sendall(b'GET / HTTP/1.1\r\n' + b'X: ' + b'y' * 20000 + b'\r\n')
        big.settimeout(10)
        assert big.recv(100).startswith(b'HTTP/1.1 400')
    finally:
        front.close()
