"""tf2_ros.transform_broadcaster."""

from ros2lite.tf2.broadcasters import TransformBroadcaster

__all__ = ['TransformBroadcaster']
