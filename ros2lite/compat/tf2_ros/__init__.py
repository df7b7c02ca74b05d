"""tf2_ros, as ros2lite provides it (``ros2lite env``): the names tf2 code imports, each the
library's own object from :mod:`ros2lite.tf2`, listed once there. Nothing is implemented here."""

from __future__ import annotations

from ros2lite import tf2 as _tf2
from ros2lite.tf2 import *  # noqa: F403

from . import buffer, static_transform_broadcaster, transform_broadcaster, transform_listener

__all__ = [
    *_tf2.__all__,
    'buffer',
    'static_transform_broadcaster',
    'transform_broadcaster',
    'transform_listener',
]
