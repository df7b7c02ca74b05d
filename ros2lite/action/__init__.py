"""Actions, as `rclpy.action` offers them: ActionServer, ActionClient and the graph queries.

from ros2lite.action import ActionServer, ActionClient, GoalResponse, CancelResponse
"""

from __future__ import annotations

from ros2lite.action.client import ActionClient, ClientGoalHandle
from ros2lite.action.graph import (
    get_action_client_names_and_types_by_node,
    get_action_names_and_types,
    get_action_server_names_and_types_by_node,
)
from ros2lite.action.server import ActionServer, CancelResponse, GoalResponse, ServerGoalHandle

__all__ = [
    'ActionClient',
    'ActionServer',
    'CancelResponse',
    'ClientGoalHandle',
    'GoalResponse',
    'ServerGoalHandle',
    'get_action_client_names_and_types_by_node',
    'get_action_names_and_types',
    'get_action_server_names_and_types_by_node',
]
