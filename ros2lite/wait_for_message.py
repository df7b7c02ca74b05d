"""`wait_for_message`: block until one message arrives on a topic (rclpy's helper).

The message is taken straight from a temporary subscription's receive thread, so this works
whether or not (and wherever) the node is being spun.
"""

from __future__ import annotations

import threading
from typing import TYPE_CHECKING

from ros2lite.qos import QoSProfile
from ros2lite.subscription import Subscription
from ros2lite.type_support import MsgT

if TYPE_CHECKING:
    from ros2lite.node import Node
    from ros2lite.transport.handles import Sample

__all__ = ['wait_for_message']


class _FirstMessage(Subscription[MsgT]):
    """A subscription that keeps the first sample it receives and wakes the waiter."""

    def __init__(
        self, node: Node, msg_type: type[MsgT] | str, topic: str, qos: QoSProfile | int
    ) -> None:
        self.first: Sample | None = None
        self.arrived = threading.Event()
        super().__init__(node, msg_type, topic, lambda _msg: None, qos)

    def _on_sample(self, sample: Sample) -> None:
        # rmw_zenoh ignores samples without an attachment; so does this
        if self.first is None and sample.attachment is not None:
            self.first = sample
            self.arrived.set()


def wait_for_message(
    msg_type: type[MsgT] | str,
    node: Node,
    topic: str,
    *,
    qos_profile: QoSProfile | int = 1,
    time_to_wait: float = -1,
) -> tuple[bool, MsgT | None]:
    """(True, message) for the next message on `topic`, or (False, None) when
    `time_to_wait` seconds (negative: no limit) pass first or the context shuts down."""
    waiter = _FirstMessage(node, msg_type, topic, qos_profile)
    context = node.context
    context.on_shutdown(waiter.arrived.set)
    try:
        waiter.arrived.wait(None if time_to_wait < 0 else time_to_wait)
        sample = waiter.first
        if sample is None:
            return False, None
        return True, waiter._deserializer()(sample.payload.to_bytes())
    finally:
        context.remove_on_shutdown(waiter.arrived.set)
        waiter.destroy()
