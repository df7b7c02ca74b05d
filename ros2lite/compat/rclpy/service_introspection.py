"""rclpy.service_introspection: names of ros2lite.service_introspection, looked up on use."""

from ._lazy import face

__getattr__ = face(
    ('ros2lite.service_introspection',), 'rclpy.service_introspection', 'service introspection'
)
