"""rclpy.service."""

from ros2lite.service import Service

__all__ = ['Service']
