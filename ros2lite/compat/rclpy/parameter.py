"""rclpy.parameter."""

from ros2lite.parameter import (
    PARAMETER_SEPARATOR_STRING,
    Parameter,
    get_parameter_value,
    parameter_value_to_python,
)
from ros2lite.parameters.files import parameter_dict_from_yaml_file

__all__ = [
    'PARAMETER_SEPARATOR_STRING',
    'Parameter',
    'get_parameter_value',
    'parameter_dict_from_yaml_file',
    'parameter_value_to_python',
]
