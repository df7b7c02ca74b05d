"""rclpy.validate_node_name: one of ROS's name rules (ros2lite.names)."""

from ros2lite.names import validate_node_name

__all__ = ['validate_node_name']
