"""`launch.actions`: ros2lite's launch actions under launch's names (ExecuteProcess
lives in ros2lite.launch.execute)."""

from ros2lite.launch import actions as _actions
from ros2lite.launch.actions import *  # noqa: F403
from ros2lite.launch.execute import ExecuteProcess

__all__ = [*_actions.__all__, 'ExecuteProcess']
