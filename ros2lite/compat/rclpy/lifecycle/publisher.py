"""rclpy.lifecycle.publisher: names of ros2lite.lifecycle, looked up on use."""

from .._lazy import face

__getattr__ = face(
    ('ros2lite.lifecycle.publisher', 'ros2lite.lifecycle'),
    'rclpy.lifecycle.publisher',
    'lifecycle nodes',
)
