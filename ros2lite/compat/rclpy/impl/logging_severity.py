"""rclpy.impl.logging_severity."""

from ros2lite.logging import LoggingSeverity

__all__ = ['LoggingSeverity']
