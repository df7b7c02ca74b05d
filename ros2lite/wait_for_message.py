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
    """A subscription that keeps the first message it receives and wakes the waiter. A
    sample that does not decode is dropped and reported, as every subscription does, and
    the wait goes on."""

    def __init__(
        self, node: Node, msg_type: type[MsgT] | str, topic: str, qos: QoSProfile | int
    ) -> None:
        self.first: MsgT | None = None
        self.arrived = threading.Event()
        super().__init__(node, msg_type, topic, lambda _msg: None, qos, on_arrival=self._arrived)

    def _arrived(self, sample: Sample) -> None:
        attachment = sample.attachment
        # rmw_zenoh ignores samples without an attachment; so does this
        if self.first is not None or attachment is None:
            return
        message = self._decoded(sample.payload.to_bytes(), attachment.to_bytes())
        if message is not None and self.first is None:
            self.first = message
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
        message = waiter.first
        if message is None:
            return False, None
        return True, message
    finally:
        context.remove_on_shutdown(waiter.arrived.set)
        waiter.destroy()
