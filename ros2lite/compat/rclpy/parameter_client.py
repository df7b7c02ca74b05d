"""rclpy.parameter_client."""

from ros2lite.parameter_client import AsyncParameterClient

__all__ = ['AsyncParameterClient']
