"""tf2_ros.buffer."""

from ros2lite.tf2.buffer import Buffer

__all__ = ['Buffer']
