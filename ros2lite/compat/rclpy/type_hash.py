"""rclpy.type_hash."""

from ros2lite.interfaces.hashing import TypeHash

__all__ = ['TypeHash']
