"""rclpy.duration."""

from ros2lite.duration import Duration, Infinite

__all__ = ['Duration', 'Infinite']
