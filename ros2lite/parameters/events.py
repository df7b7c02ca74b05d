"""/parameter_events: every declare, set and undeclare of a node, as rclpy publishes them."""

from __future__ import annotations

from typing import TYPE_CHECKING

from ros2lite.parameter import Parameter

if TYPE_CHECKING:
    from ros2lite.msgs.rcl_interfaces.msg import ParameterEvent
    from ros2lite.node_interface import NodeInterface
    from ros2lite.publisher import Publisher

TOPIC = "/parameter_events"
TYPE = "rcl_interfaces/msg/ParameterEvent"


class ParameterEventPublisher:
    """Turns a store's (new, changed, deleted) report into one ParameterEvent message."""

    def __init__(self, node: NodeInterface) -> None:
        from ros2lite.qos import qos_profile_parameter_events

        self._node = node
        self._publisher: Publisher[ParameterEvent] = node.create_publisher(
            TYPE, TOPIC, qos_profile_parameter_events
        )

    def __call__(
        self, new: list[Parameter], changed: list[Parameter], deleted: list[Parameter]
    ) -> None:
        """Publish one event for the parameters declared, changed and undeclared."""
        from ros2lite.interfaces import get_interface

        event_type: type[ParameterEvent] = get_interface(TYPE)
        event = event_type(
            stamp=self._node.get_clock().now().to_msg(),
            node=self._node.get_fully_qualified_name(),
            new_parameters=[p.to_parameter_msg() for p in new],
            changed_parameters=[p.to_parameter_msg() for p in changed],
            deleted_parameters=[p.to_parameter_msg() for p in deleted],
        )
        self._publisher.publish(event)
