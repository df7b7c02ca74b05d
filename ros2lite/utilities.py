"""Small facts rclpy's utilities module offers: argument stripping, timeouts as rcl takes
them, and which middleware this is.
"""

from __future__ import annotations

from ros2lite.duration import S_TO_NS
from ros2lite.runtime.arguments import remove_ros_args

__all__ = [
    'RMW_IMPLEMENTATION',
    'get_available_rmw_implementations',
    'get_rmw_implementation_identifier',
    'remove_ros_args',
    'timeout_sec_to_nsec',
]

#: the middleware ros2lite speaks on the wire, by the name ROS gives it
RMW_IMPLEMENTATION = 'rmw_zenoh_cpp'


def get_rmw_implementation_identifier() -> str:
    """'rmw_zenoh_cpp': ros2lite is wire-compatible with it, and with nothing else."""
    return RMW_IMPLEMENTATION


def get_available_rmw_implementations() -> set[str]:
    """The middlewares this process could use: only rmw_zenoh_cpp's wire."""
    return {RMW_IMPLEMENTATION}


def timeout_sec_to_nsec(timeout_sec: float | None) -> int:
    """A timeout as rcl takes it: None or negative means forever (-1), else nanoseconds."""
    if timeout_sec is None or timeout_sec < 0:
        return -1
    return int(timeout_sec * S_TO_NS)
