"""rclpy.context: the process context."""

from ros2lite.context import Context, default_context

__all__ = ['Context', 'default_context']
