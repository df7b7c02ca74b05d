"""tf2_ros, as ros2lite provides it (``ros2lite env``): the names tf2 code imports, each the
library's own object from :mod:`ros2lite.tf2`. Nothing is implemented here."""

from __future__ import annotations

from ros2lite.tf2 import (
    Buffer,
    BufferCore,
    ConnectivityException,
    ExtrapolationException,
    InvalidArgumentException,
    LookupException,
    StaticTransformBroadcaster,
    TimeoutException,
    TransformBroadcaster,
    TransformException,
    TransformListener,
)

from . import buffer, static_transform_broadcaster, transform_broadcaster, transform_listener

__all__ = [
    'Buffer',
    'BufferCore',
    'ConnectivityException',
    'ExtrapolationException',
    'InvalidArgumentException',
    'LookupException',
    'StaticTransformBroadcaster',
    'TimeoutException',
    'TransformBroadcaster',
    'TransformException',
    'TransformListener',
    'buffer',
    'static_transform_broadcaster',
    'transform_broadcaster',
    'transform_listener',
]
