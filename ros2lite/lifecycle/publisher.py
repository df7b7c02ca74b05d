"""A publisher that sends only while its lifecycle node is active (rclpy's LifecyclePublisher)."""

from __future__ import annotations

from typing import TYPE_CHECKING, Generic

from ros2lite.lifecycle.managed_entity import SimpleManagedEntity
from ros2lite.publisher import Publisher
from ros2lite.qos import QoSProfile
from ros2lite.type_support import MsgT

if TYPE_CHECKING:
    from ros2lite.node import Node

__all__ = ['LifecyclePublisher']


class LifecyclePublisher(SimpleManagedEntity, Publisher[MsgT], Generic[MsgT]):
    """Created by `LifecycleNode.create_lifecycle_publisher`; `publish` is silently dropped
    until the node activates it (and again after it deactivates)."""

    def __init__(
        self, node: Node, msg_type: type[MsgT] | str, topic: str, qos: QoSProfile | int
    ) -> None:
        SimpleManagedEntity.__init__(self)
        Publisher.__init__(self, node, msg_type, topic, qos)

    @SimpleManagedEntity.when_enabled
    def publish(self, msg: MsgT | bytes | bytearray | memoryview) -> None:
        """Publish `msg` if the node is active; otherwise drop it."""
        Publisher.publish(self, msg)
