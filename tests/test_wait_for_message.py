"""wait_for_message: the next message of a topic without spinning anything, or False when
time is up."""

from __future__ import annotations

import threading
from typing import Any

from ros2lite.interfaces import get_interface
from ros2lite.node import Node
from ros2lite.wait_for_message import wait_for_message
from tests.spinning import wait_matched

Int32 = get_interface('std_msgs/msg/Int32')


def test_next_message_or_timeout(ros_context: Any) -> None:
    node = Node('waiter', context=ros_context)
    assert wait_for_message(Int32, node, 'nobody_talks', time_to_wait=0.2) == (False, None)
    pub = Node('teller', context=ros_context).create_publisher(Int32, 'numbers', 10)

    def publish_when_heard() -> None:
        wait_matched(pub, 1, timeout=10)
        pub.publish(Int32(data=42))

    threading.Thread(target=publish_when_heard).start()
    ok, msg = wait_for_message(Int32, node, 'numbers', time_to_wait=10)
    assert ok and msg == Int32(data=42)
    assert node.count_subscribers('numbers') == 0  # its subscription is gone again


def test_a_sample_that_does_not_decode_is_skipped(ros_context: Any) -> None:
    """A publisher of raw bytes sends junk first: it is dropped and reported, and the next
    sample that decodes is the message."""
    node = Node('picky_waiter', context=ros_context)
    pub = Node('mixed_teller', context=ros_context).create_publisher(Int32, 'mixed', 10)

    def publish_when_heard() -> None:
        wait_matched(pub, 1, timeout=10)
        pub.publish(b'\x00\x01\x00\x00')  # a header and no int32
        pub.publish(Int32(data=7))

    threading.Thread(target=publish_when_heard).start()
    ok, msg = wait_for_message(Int32, node, 'mixed', time_to_wait=10)
    assert ok and msg == Int32(data=7)
