"""rclpy.validate_namespace: one of ROS's name rules (ros2lite.names)."""

from ros2lite.names import validate_namespace

__all__ = ['validate_namespace']
