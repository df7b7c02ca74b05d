"""tf2_ros.static_transform_broadcaster."""

from ros2lite.tf2.broadcasters import StaticTransformBroadcaster

__all__ = ['StaticTransformBroadcaster']
