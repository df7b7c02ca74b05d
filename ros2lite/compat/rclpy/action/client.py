"""rclpy.action.client."""

from ros2lite.action.client import ActionClient, ClientGoalHandle

__all__ = ['ActionClient', 'ClientGoalHandle']
