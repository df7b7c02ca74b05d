"""`doctor hello` / `wtf hello`: ros2doctor's table of hellos out and in, by topic and by
multicast, with another host played by the test (its hellos name another host); multicast
stays on this machine (127.0.0.1, TTL 0) on a port of its own."""

from __future__ import annotations

import threading
from collections.abc import Callable
from typing import Any

import pytest

from ros2lite.interfaces import get_interface
from ros2lite.node import Node
from ros2lite.tools.multicast import MulticastSender
from tests.cli.conftest import Result
from tests.spinning import free_port, wait_until
from tests.tools.test_multicast import multicast_on_loopback

String = get_interface('std_msgs/msg/String')
OTHER = "hello, it's me otherhost"


def local(port: int) -> list[str]:
    if not multicast_on_loopback(port):
        pytest.skip('this machine has no multicast route on loopback')
    return ['--port', str(port), '--interface', '127.0.0.1', '--ttl', '0']


def table(*rows: tuple[str, int]) -> list[str]:
    head = '{:<15} {:<20} {:<10}'.format('', 'Hostname', 'Msg Count /1.0s')
    return [head] + ['{:<15} {:<20} {:<10}'.format('', host, n) for host, n in rows]


def test_once_alone(run: Callable[..., Result], ros_router: str) -> None:
    port = free_port()
    result = run('wtf', 'hello', '--once', *local(port))
    assert (result.code, result.err) == (0, '')
    assert result.out.splitlines() == [
        'MULTIMACHINE COMMUNICATION SUMMARY',
        'Topic: /canyouhearme, Published Msg Count: 1',
        'Subscribed from:',
        *table(),  # its own hellos do not count
        f'Multicast Group/Port: 225.0.0.1/{port}, Sent Msg Count: 1',
        'Received from:',
        *table(),
        '-' * 60,
    ]


def test_hears_another_host(ros_context: Any, processes: Any) -> None:
    port = free_port()
    proc = processes.cli('doctor', 'hello', '-t', '/hello_test', *local(port))
    lines: list[str] = []
    reader = threading.Thread(target=lambda: lines.extend(proc.stdout), daemon=True)
    reader.start()
    node = Node('other_host', context=ros_context)
    pub = node.create_publisher(String, '/hello_test', 10)
    sender = MulticastSender(port=port, ttl=0, interface='127.0.0.1')

    def say_hello() -> None:
        pub.publish(String(data=OTHER))
        sender.send(OTHER.encode())

    def heard_both() -> bool:
        text = ''.join(lines)
        return (
            f'{"":<15} {"otherhost":<20}'
            in text.partition('Multicast')[0].rpartition('Subscribed')[2]
            and f'{"":<15} {"otherhost":<20}' in text.rpartition('Received from:')[2]
        )

    try:
        wait_until(lambda: pub.get_subscription_count() >= 1, timeout=15)
        wait_until(heard_both, timeout=20, interval=0.1, step=say_hello)
    finally:
        sender.close()
    _out, err = processes.stop(proc)
    reader.join(5)
    assert proc.returncode == 0 and 'Traceback' not in err, err
    out = [line.rstrip('\n') for line in lines]
    assert out[0] == 'MULTIMACHINE COMMUNICATION SUMMARY'
    assert out[1].startswith('Topic: /hello_test, Published Msg Count: ')
    published = [int(x.rpartition(' ')[2]) for x in out if x.startswith('Topic: ')]
    assert all(8 <= n <= 12 for n in published[1:-1]), published  # 10 a second
    heard = [x for x in out if 'otherhost' in x]
    assert heard and all(x.startswith(' ' * 16 + 'otherhost ') for x in heard)
