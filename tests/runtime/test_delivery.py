"""The typed hot loop (ros2lite.runtime.delivery): batches keep their order whatever happens
in them — a bad sample is dropped and the rest delivered, a callback's error propagates and the
rest of the batch is delivered later, a callback with MessageInfo gets its info."""

from __future__ import annotations

import struct
import time
from typing import Any

import pytest

from ros2lite.executors import SingleThreadedExecutor
from ros2lite.node import Node
from ros2lite.task import Future
from tests.spinning import queued, spin_until, wait_for_route, wait_until

STRING_HASH = 'RIHS01_df668c740482bbd48fb39d76a70dfd4bd59db1288021743503259e948f6b1a18'


def _cdr(text: str) -> bytes:
    raw = text.encode() + b'\x00'
    return b'\x00\x01\x00\x00' + struct.pack('<I', len(raw)) + raw


def _put(session: Any, key: str, payloads: list[bytes]) -> None:
    for seq, payload in enumerate(payloads, 1):
        attachment = struct.pack('<qqB', seq, time.time_ns(), 16) + bytes([7]) * 16
        session.put(key, payload, attachment=attachment)


def _subscription(node: Node, topic: str, callback: Any, alien: Any) -> tuple[Any, str]:
    sub = node.create_subscription('std_msgs/msg/String', topic, callback, 100)
    wait_for_route(alien, node, topic)
    return sub, sub._ep.key


def test_a_bad_sample_inside_a_batch_is_dropped_and_the_rest_delivered(
    ros_context: Any, alien_session: Any
) -> None:
    node = Node('delivery_bad', context=ros_context)
    got: list[str] = []
    sub, key = _subscription(node, '/delivery_bad', lambda m: got.append(m.data), alien_session)
    _put(alien_session, key, [_cdr('a'), b'\x00\x01\x00\x00junk', _cdr('b'), _cdr('c')])
    wait_until(lambda: len(queued(sub)) == 4)
    executor = SingleThreadedExecutor(context=ros_context)
    executor.add_node(node)
    spin_until(executor, lambda: got == ['a', 'b', 'c'])
    assert sub.bad_samples is not None and sub.bad_samples.total == 1
    executor.shutdown()


def test_a_callback_error_mid_batch_leaves_the_rest_for_later(
    ros_context: Any, alien_session: Any
) -> None:
    node = Node('delivery_raise', context=ros_context)
    got: list[str] = []

    def callback(msg: Any) -> None:
        got.append(msg.data)
        if msg.data == '2':
            raise RuntimeError('user bug')

    sub, key = _subscription(node, '/delivery_raise', callback, alien_session)
    _put(alien_session, key, [_cdr(str(i)) for i in range(6)])
    wait_until(lambda: len(queued(sub)) == 6)
    executor = SingleThreadedExecutor(context=ros_context)
    executor.add_node(node)
    with pytest.raises(RuntimeError, match='user bug'):
        executor.spin_until_future_complete(Future(), timeout_sec=5)  # batches
    assert got == ['0', '1', '2']
    spin_until(executor, lambda: len(got) == 6)
    assert got == [str(i) for i in range(6)]
    executor.shutdown()


def test_message_info_comes_with_each_message_of_a_batch(
    ros_context: Any, alien_session: Any
) -> None:
    node = Node('delivery_info', context=ros_context)
    got: list[tuple[str, int]] = []
    sub, key = _subscription(
        node,
        '/delivery_info',
        lambda m, info: got.append((m.data, info.publication_sequence_number)),
        alien_session,
    )
    _put(alien_session, key, [_cdr('x'), b'junk', _cdr('y'), _cdr('z')])
    wait_until(lambda: len(queued(sub)) == 4)
    executor = SingleThreadedExecutor(context=ros_context)
    executor.add_node(node)
    spin_until(executor, lambda: len(got) == 3)
    assert got == [('x', 1), ('y', 3), ('z', 4)]
    executor.shutdown()
