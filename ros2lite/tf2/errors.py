"""tf2's exceptions, by tf2's names: code written for tf2_ros catches these."""

from __future__ import annotations

from ros2lite.exceptions import Ros2liteError

__all__ = [
    'ConnectivityException',
    'ExtrapolationException',
    'InvalidArgumentException',
    'LookupException',
    'TimeoutException',
    'TransformException',
]


class TransformException(Ros2liteError):
    """A transform could not be had; the base the others share (catch this one)."""


class ConnectivityException(TransformException):
    """The two frames are in different trees: no chain of parents joins them."""


class LookupException(TransformException):
    """A frame is not known to the buffer (or the tree has a loop)."""


class ExtrapolationException(TransformException):
    """The time asked for is outside what the buffer holds for some frame of the chain."""


class InvalidArgumentException(TransformException):
    """A frame id that tf2 never accepts: empty, or starting with '/'."""


class TimeoutException(TransformException):
    """The transform did not become available within the timeout."""
