"""rclpy.action.server."""

from ros2lite.action.server import ActionServer, CancelResponse, GoalResponse, ServerGoalHandle

__all__ = ['ActionServer', 'CancelResponse', 'GoalResponse', 'ServerGoalHandle']
