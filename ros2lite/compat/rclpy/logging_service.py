"""rclpy.logging_service."""

from ros2lite.logging_service import LoggingService

__all__ = ['LoggingService']
