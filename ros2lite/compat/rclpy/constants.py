"""rclpy.constants."""

from ros2lite.duration import S_TO_NS

__all__ = ['S_TO_NS']
