"""A publisher that sends only while its lifecycle node is active (rclpy's LifecyclePublisher)."""

from __future__ import annotations

from typing import Any

from ros2lite.lifecycle.managed_entity import SimpleManagedEntity
from ros2lite.publisher import Publisher
from ros2lite.qos import QoSProfile

__all__ = ['LifecyclePublisher']


class LifecyclePublisher(SimpleManagedEntity, Publisher):
    """Created by `LifecycleNode.create_lifecycle_publisher`; `publish` is silently dropped
    until the node activates it (and again after it deactivates)."""

    def __init__(self, node: Any, msg_type: Any, topic: str, qos: QoSProfile | int) -> None:
        SimpleManagedEntity.__init__(self)
        Publisher.__init__(self, node, msg_type, topic, qos)

    @SimpleManagedEntity.when_enabled
    def publish(self, msg: Any) -> None:
        """Publish `msg` if the node is active; otherwise drop it."""
        Publisher.publish(self, msg)
