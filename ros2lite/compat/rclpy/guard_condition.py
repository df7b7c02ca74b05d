"""rclpy.guard_condition."""

from ros2lite.executable import GuardCondition

__all__ = ['GuardCondition']
