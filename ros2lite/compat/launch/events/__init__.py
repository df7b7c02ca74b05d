"""`launch.events`: ros2lite's launch events under launch's names."""

from ros2lite.launch.events import Event, ExecutionComplete, Shutdown, matches_action

from . import process

__all__ = ['Event', 'ExecutionComplete', 'Shutdown', 'matches_action', 'process']
