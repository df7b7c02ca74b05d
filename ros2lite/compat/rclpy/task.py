"""rclpy.task."""

from ros2lite.task import Future, Task

__all__ = ['Future', 'Task']
