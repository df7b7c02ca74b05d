"""ros2lite's launch system: launch descriptions made of actions, substitutions, conditions
and event handlers, run by a :class:`LaunchService` — modelled on ROS 2's launch and
launch_ros, written for ros2lite (processes through :mod:`ros2lite.util.process`, packages
through :mod:`ros2lite.pkg.index`).

Python launch files written for ROS import ``launch`` and ``launch_ros``; those names are
faces over this package in ``ros2lite/compat``. XML and YAML launch files are read by
:mod:`.frontend`. The CLI verb is ``ros2lite launch`` (:mod:`.api`).
"""

from __future__ import annotations

from pathlib import Path

from .actions import Action, LaunchDescription, LaunchDescriptionEntity
from .conditions import Condition
from .context import LaunchContext
from .errors import LaunchError, SubstitutionFailure
from .event_handlers import EventHandler
from .events import Event
from .service import LaunchService
from .sources import use_frontend
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


def _read_frontend_file(path: Path, kind: str) -> LaunchDescription:
    """An XML or YAML launch file read by :mod:`.frontend`, imported when the first such file
    is read (a Python launch does not pay for it)."""
    from .frontend.loader import load_frontend_file

    return load_frontend_file(path, kind)


use_frontend(_read_frontend_file)
