"""`launch.actions`: ros2lite's launch actions under launch's names (the flow actions live in
ros2lite.launch.flow, ExecuteProcess in ros2lite.launch.execute)."""

from ros2lite.launch import actions as _actions
from ros2lite.launch import flow as _flow
from ros2lite.launch.actions import *  # noqa: F403
from ros2lite.launch.execute import ExecuteProcess
from ros2lite.launch.flow import *  # noqa: F403

__all__ = [*_actions.__all__, *_flow.__all__, 'ExecuteProcess']
