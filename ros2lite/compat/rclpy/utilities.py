"""rclpy.utilities."""

from ros2lite import ok, shutdown, try_shutdown
from ros2lite.context import default_context as get_default_context
from ros2lite.utilities import (
    get_available_rmw_implementations,
    get_rmw_implementation_identifier,
    remove_ros_args,
    timeout_sec_to_nsec,
)

__all__ = [
    'get_available_rmw_implementations',
    'get_default_context',
    'get_rmw_implementation_identifier',
    'ok',
    'remove_ros_args',
    'shutdown',
    'timeout_sec_to_nsec',
    'try_shutdown',
]
