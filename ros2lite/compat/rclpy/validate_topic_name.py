"""rclpy.validate_topic_name: one of ROS's name rules (ros2lite.names)."""

from ros2lite.names import validate_topic_name

__all__ = ['validate_topic_name']
