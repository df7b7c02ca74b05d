"""rclpy.parameter."""

from ros2lite.parameter import (
    PARAMETER_SEPARATOR_STRING,
    Parameter,
    get_parameter_value,
    parameter_value_to_python,
)

__all__ = [
    'PARAMETER_SEPARATOR_STRING',
    'Parameter',
    'get_parameter_value',
    'parameter_value_to_python',
]
