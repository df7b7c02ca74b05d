"""`launch`, as ROS launch files import it: ros2lite's launch library under launch's names
(names only; the code is in ros2lite.launch)."""

from ros2lite import launch as _launch
from ros2lite.launch import *  # noqa: F403
from ros2lite.launch.sources import LaunchDescriptionSource

from . import (
    actions,
    conditions,
    event_handlers,
    events,
    launch_description_sources,
    substitutions,
    utilities,
)

__all__ = [
    *_launch.__all__,
    'LaunchDescriptionSource',
    'actions',
    'conditions',
    'event_handlers',
    'events',
    'launch_description_sources',
    'substitutions',
    'utilities',
]
