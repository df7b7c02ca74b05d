"""rclpy.node: the Node."""

from ros2lite.node import Node

__all__ = ['Node']
