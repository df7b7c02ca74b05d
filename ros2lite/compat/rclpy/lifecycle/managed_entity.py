"""rclpy.lifecycle.managed_entity: names of ros2lite.lifecycle, looked up on use."""

from .._lazy import face

__getattr__ = face(
    ('ros2lite.lifecycle.managed_entity', 'ros2lite.lifecycle'),
    'rclpy.lifecycle.managed_entity',
    'lifecycle nodes',
)
