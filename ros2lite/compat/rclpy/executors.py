"""rclpy.executors: the executors of :mod:`ros2lite.executors`, and `await_or_execute`, which
rclpy keeps here and ros2lite beside the action server that uses it."""

from ros2lite.action.server import await_or_execute
from ros2lite.executors import *  # noqa: F403
from ros2lite.executors import __all__ as _executors_all

__all__ = [*_executors_all, 'await_or_execute']
