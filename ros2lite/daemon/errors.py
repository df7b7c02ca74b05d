"""The daemon's own error, apart so that naming it loads neither zenoh nor the router."""

from __future__ import annotations

from ros2lite.exceptions import Ros2liteError

__all__ = ["DaemonError"]


class DaemonError(Ros2liteError, RuntimeError):
    """The daemon could not be started or stopped; the message says why (and where the log is)."""
