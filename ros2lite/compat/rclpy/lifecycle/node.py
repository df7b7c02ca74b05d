"""rclpy.lifecycle.node: names of ros2lite.lifecycle, looked up on use."""

from .._lazy import face

__getattr__ = face(
    ('ros2lite.lifecycle.node', 'ros2lite.lifecycle'), 'rclpy.lifecycle.node', 'lifecycle nodes'
)
