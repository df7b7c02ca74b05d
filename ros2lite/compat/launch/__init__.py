"""`launch`, as ROS launch files import it: ros2lite's launch library under launch's names
(names only; the code is in ros2lite.launch)."""

from ros2lite.launch import (
    Action,
    Condition,
    Event,
    EventHandler,
    LaunchContext,
    LaunchDescription,
    LaunchDescriptionEntity,
    LaunchService,
    SomeSubstitutionsType,
    Substitution,
)
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
    'Action',
    'Condition',
    'Event',
    'EventHandler',
    'LaunchContext',
    'LaunchDescription',
    'LaunchDescriptionEntity',
    'LaunchDescriptionSource',
    'LaunchService',
    'SomeSubstitutionsType',
    'Substitution',
    'actions',
    'conditions',
    'event_handlers',
    'events',
    'launch_description_sources',
    'substitutions',
    'utilities',
]
