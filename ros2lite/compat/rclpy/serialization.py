"""rclpy.serialization."""

from ros2lite.serialization import deserialize_message, serialize_message

__all__ = ['deserialize_message', 'serialize_message']
