"""tf2: coordinate frames over time. A buffer of every frame's recent transforms, the
listener that fills it from `/tf` and `/tf_static`, the broadcasters that send them, and the
quaternion arithmetic beneath; `compat/tf2_ros` gives these tf2_ros's module names."""

from ros2lite.tf2.broadcasters import StaticTransformBroadcaster, TransformBroadcaster
from ros2lite.tf2.buffer import Buffer
from ros2lite.tf2.core import DEFAULT_CACHE_TIME, BufferCore
from ros2lite.tf2.errors import (
    ConnectivityException,
    ExtrapolationException,
    InvalidArgumentException,
    LookupException,
    TimeoutException,
    TransformException,
)
from ros2lite.tf2.listener import TransformListener

__all__ = [
    'DEFAULT_CACHE_TIME',
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
]
