"""rclpy.action: action servers, clients and the graph queries."""

from ros2lite.action import (
    ActionClient,
    ActionServer,
    CancelResponse,
    GoalResponse,
    get_action_client_names_and_types_by_node,
    get_action_names_and_types,
    get_action_server_names_and_types_by_node,
)

__all__ = [
    'ActionClient',
    'ActionServer',
    'CancelResponse',
    'GoalResponse',
    'get_action_client_names_and_types_by_node',
    'get_action_names_and_types',
    'get_action_server_names_and_types_by_node',
]
