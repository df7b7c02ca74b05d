"""rclpy.lifecycle: names of ros2lite.lifecycle (managed nodes), looked up on use."""

from .._lazy import face

__getattr__ = face(('ros2lite.lifecycle',), 'rclpy.lifecycle', 'lifecycle nodes')
