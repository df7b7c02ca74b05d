"""rclpy.validate_parameter_name."""

from ros2lite.parameters.store import validate_parameter_name

__all__ = ['validate_parameter_name']
