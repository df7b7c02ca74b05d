"""The one error of robot descriptions: a URDF that cannot be read, a resource refused."""

from __future__ import annotations

from ros2lite.exceptions import Ros2liteError

__all__ = ['ResourceNotFoundError', 'UrdfError']


class UrdfError(Ros2liteError, ValueError):
    """A robot description (or a resource URI in it) that cannot be used; one line."""


class ResourceNotFoundError(UrdfError, FileNotFoundError):
    """A well-formed, allowed resource URI naming no file (callers may catch either base)."""
