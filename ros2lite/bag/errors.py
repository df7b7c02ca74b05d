"""Errors of bags, under ros2lite's one base."""

from __future__ import annotations

from ros2lite.exceptions import Ros2liteError

__all__ = ['BagError', 'MetadataError']


class BagError(Ros2liteError):
    """A bag cannot be read or written; the message says which file and why."""


class MetadataError(BagError, ValueError):
    """metadata.yaml (or a `rosbag2` record) is unreadable or misses a required key."""
