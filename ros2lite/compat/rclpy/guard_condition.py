"""rclpy.guard_condition."""

from ros2lite.runtime.executable import GuardCondition

__all__ = ['GuardCondition']
