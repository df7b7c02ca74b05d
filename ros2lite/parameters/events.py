"""/parameter_events: every declare, set and undeclare of a node, as rclpy publishes them."""

from __future__ import annotations

from typing import Any

from ros2lite.parameter import Parameter

TOPIC = "/parameter_events"
TYPE = "rcl_interfaces/msg/ParameterEvent"


class ParameterEventPublisher:
    """Turns a store's (new, changed, deleted) report into one ParameterEvent message."""

    def __init__(self, node: Any) -> None:
        from ros2lite.qos import qos_profile_parameter_events

        self._node = node
        self._publisher = node.create_publisher(TYPE, TOPIC, qos_profile_parameter_events)

    def __call__(
        self, new: list[Parameter], changed: list[Parameter], deleted: list[Parameter]
    ) -> None:
        from ros2lite.interfaces import get_interface

        event = get_interface(TYPE)(
            stamp=self._node.get_clock().now().to_msg(),
            node=self._node.get_fully_qualified_name(),
            new_parameters=[p.to_parameter_msg() for p in new],
            changed_parameters=[p.to_parameter_msg() for p in changed],
            deleted_parameters=[p.to_parameter_msg() for p in deleted],
        )
        self._publisher.publish(event)
