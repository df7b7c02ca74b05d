"""rclpy.expand_topic_name: one of ROS's name rules (ros2lite.names)."""

from ros2lite.names import expand_topic_name

__all__ = ['expand_topic_name']
