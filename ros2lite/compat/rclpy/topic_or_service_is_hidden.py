"""rclpy.topic_or_service_is_hidden: one of ROS's name rules (ros2lite.names)."""

from ros2lite.names import topic_or_service_is_hidden

__all__ = ['topic_or_service_is_hidden']
