"""Which ROS 2 distribution ros2lite answers as: Jazzy, unless ``ROS_DISTRO`` names Kilted
or Rolling, whose names it then uses where they differ from Jazzy's.

What differs so far: turtlesim's interfaces live in the `turtlesim_msgs` package from
Kilted on (Jazzy's turtlesim node serves `turtlesim/…`; :func:`other_distro_name` says so
when a name of one meets a node of the other), and bags record the distro in their
metadata, as rosbag2 does. The wire is the same: Kilted's type hashes for the bundled
interfaces equal Jazzy's (a test compares them with Kilted's own type descriptions).
"""

from __future__ import annotations

import os
from collections.abc import Mapping

__all__ = ['DEFAULT_DISTRO', 'DISTROS', 'other_distro_name', 'ros_distro', 'turtlesim_interfaces']

DEFAULT_DISTRO = 'jazzy'
DISTROS = ('jazzy', 'kilted', 'rolling')
"""The distributions ros2lite speaks, oldest first; any other name means the default."""


def ros_distro(env: Mapping[str, str] | None = None) -> str:
    """The distribution named by ``ROS_DISTRO`` if ros2lite speaks it, else Jazzy."""
    value = (os.environ if env is None else env).get('ROS_DISTRO', '').strip().lower()
    return value if value in DISTROS else DEFAULT_DISTRO


def turtlesim_interfaces(distro: str | None = None) -> str:
    """The package whose interfaces turtlesim's nodes use in `distro` (default: the current
    one): `turtlesim` in Jazzy, `turtlesim_msgs` from Kilted on."""
    distro = ros_distro() if distro is None else distro
    return 'turtlesim' if distro == DEFAULT_DISTRO else 'turtlesim_msgs'


# interface packages renamed between distributions: Jazzy's name → Kilted's
_RENAMED = {'turtlesim': 'turtlesim_msgs'}


def other_distro_name(wanted: str, served: list[str]) -> str:
    """What to do when `wanted` (``pkg/kind/Name``) is not among the `served` types but one of
    them is the same interface under another distribution's package name, in words for a
    warning (``''`` otherwise): a course for Kilted types ``turtlesim_msgs/srv/Spawn`` at a
    turtlesim serving Jazzy's ``turtlesim/srv/Spawn``, or the other way round."""
    package, _, rest = wanted.partition('/')
    for old, new in _RENAMED.items():
        if package == new and f'{old}/{rest}' in served:
            return (
                f"{new} is Kilted's name for these interfaces: start the node with "
                f'ROS_DISTRO=kilted to serve it, or type {old}/{rest}'
            )
        if package == old and f'{new}/{rest}' in served:
            return (
                f'the node runs with ROS_DISTRO=kilted, which names them {new}: type '
                f'{new}/{rest}, or start it without ROS_DISTRO=kilted'
            )
    return ''
