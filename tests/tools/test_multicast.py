"""One multicast datagram over loopback (TTL 0: nothing leaves the machine), and the checks
on addresses. Skipped where the machine cannot do multicast on loopback at all."""

from __future__ import annotations

import threading
import time

import pytest

from ros2lite.tools.multicast import HELLO, MulticastError, receive, send
from tests.spinning import free_port

LOOPBACK = {'interface': '127.0.0.1'}


def multicast_on_loopback(port: int) -> bool:
    try:
        send(b'probe', port=port, ttl=0, **LOOPBACK)
    except MulticastError:
        return False
    return True


def test_send_then_receive_on_loopback() -> None:
    port = free_port()
    if not multicast_on_loopback(port):
        pytest.skip('this machine has no multicast route on loopback')
    got: list[tuple[bytes, tuple[str, int]]] = []
    receiver = threading.Thread(
        target=lambda: got.append(receive(port=port, timeout=20, **LOOPBACK))
    )
    receiver.start()
    deadline = time.monotonic() + 20
    while receiver.is_alive() and time.monotonic() < deadline:
        send(port=port, ttl=0, **LOOPBACK)  # until the receiver has joined and heard one
        receiver.join(timeout=0.1)
    assert got and got[0][0] == HELLO
    assert got[0][1][0] == '127.0.0.1'


def test_receive_times_out() -> None:
    with pytest.raises(TimeoutError, match=r'no datagram to 225\.0\.0\.1:\d+ within 0\.2 s'):
        receive(port=free_port(), timeout=0.2, **LOOPBACK)


@pytest.mark.parametrize(
    ('options', 'message'),
    [
        ({'group': '10.0.0.1'}, "'10.0.0.1' is not a multicast address"),
        ({'group': 'nowhere'}, "'nowhere' is not an IPv4 address"),
        ({'port': 0}, 'port 0 is out of range'),
        ({'ttl': 256}, 'TTL 256 is out of range'),
        ({'interface': 'eth0'}, "'eth0' is not the IPv4 address of an interface"),
    ],
)
def test_bad_settings(options: dict[str, object], message: str) -> None:
    with pytest.raises(MulticastError, match=message):
        send(**options)  # type: ignore[arg-type]
