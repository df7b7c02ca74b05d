"""ros2lite's launch system: launch descriptions made of actions, substitutions, conditions
and event handlers, run by a :class:`LaunchService` — modelled on ROS 2's launch and
launch_ros, written for ros2lite (processes through :mod:`ros2lite.process`, packages
through :mod:`ros2lite.pkg.index`).

Python launch files written for ROS import ``launch`` and ``launch_ros``; those names are
faces over this package in ``ros2lite/compat``. XML and YAML launch files are read by
:mod:`.frontend`. The CLI verb is ``ros2lite launch`` (:mod:`.api`).
"""

from __future__ import annotations

from .actions import Action, LaunchDescription, LaunchDescriptionEntity
from .conditions import Condition
from .context import LaunchContext
from .errors import LaunchError, SubstitutionFailure
from .event_handlers import EventHandler
from .events import Event
from .service import LaunchService
from .substitutions import SomeSubstitutionsType, Substitution

__all__ = [
    'Action',
    'Condition',
    'Event',
    'EventHandler',
    'LaunchContext',
    'LaunchDescription',
    'LaunchDescriptionEntity',
    'LaunchError',
    'LaunchService',
    'SomeSubstitutionsType',
    'Substitution',
    'SubstitutionFailure',
]
