"""rclpy.parameter_service."""

from ros2lite.parameters.services import ParameterService

__all__ = ['ParameterService']
