"""rclpy.validate_full_topic_name: one of ROS's name rules (ros2lite.names)."""

from ros2lite.names import validate_full_topic_name

__all__ = ['validate_full_topic_name']
