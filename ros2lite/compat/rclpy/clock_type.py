"""rclpy.clock_type."""

from ros2lite.time import ClockType

__all__ = ['ClockType']
