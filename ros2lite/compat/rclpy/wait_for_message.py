"""rclpy.wait_for_message."""

from ros2lite.wait_for_message import wait_for_message

__all__ = ['wait_for_message']
