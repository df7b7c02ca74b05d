"""rclpy.timer."""

from ros2lite.timer import Timer

__all__ = ['Timer']
