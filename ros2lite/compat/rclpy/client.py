"""rclpy.client."""

from ros2lite.client import Client

__all__ = ['Client']
