"""The simulator's one error: a world, robot or option it cannot use, said in one line."""

from __future__ import annotations

from ros2lite.exceptions import Ros2liteError

__all__ = ['SimError']


class SimError(Ros2liteError, ValueError):
    """A world file, robot model or setting the simulator cannot use."""
