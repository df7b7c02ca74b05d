"""tf2_ros.transform_listener."""

from ros2lite.tf2.listener import TransformListener

__all__ = ['TransformListener']
