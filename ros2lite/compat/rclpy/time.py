"""rclpy.time."""

from ros2lite.time import Time

__all__ = ['Time']
