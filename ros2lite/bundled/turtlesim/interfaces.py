"""turtlesim's interface classes for the distro we speak (:mod:`ros2lite.pkg.distro`): the
`turtlesim` package's in Jazzy, `turtlesim_msgs`' from Kilted on, where upstream moved them.
Every turtlesim executable imports them from here, so nodes and tools of one process tree
agree; both packages define the same types, so the code using them is the same."""

from __future__ import annotations

from typing import TYPE_CHECKING

from ros2lite.pkg.distro import turtlesim_interfaces

__all__ = [
    'Color',
    'Kill',
    'Pose',
    'RotateAbsolute',
    'SetPen',
    'Spawn',
    'TeleportAbsolute',
    'TeleportRelative',
]

# the type checker reads Jazzy's (their stubs); at run time the distro decides
if TYPE_CHECKING or turtlesim_interfaces() == 'turtlesim':
    from ros2lite.msgs.turtlesim.action import RotateAbsolute
    from ros2lite.msgs.turtlesim.msg import Color, Pose
    from ros2lite.msgs.turtlesim.srv import (
        Kill,
        SetPen,
        Spawn,
        TeleportAbsolute,
        TeleportRelative,
    )
else:
    from ros2lite.msgs.turtlesim_msgs.action import RotateAbsolute
    from ros2lite.msgs.turtlesim_msgs.msg import Color, Pose
    from ros2lite.msgs.turtlesim_msgs.srv import (
        Kill,
        SetPen,
        Spawn,
        TeleportAbsolute,
        TeleportRelative,
    )
