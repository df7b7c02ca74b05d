"""`launch.events`: ros2lite's launch events under launch's names."""

from ros2lite.launch import events as _events
from ros2lite.launch.events import *  # noqa: F403

from . import process

__all__ = [*_events.__all__, 'process']
