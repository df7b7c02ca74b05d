"""rclpy.clock."""

from ros2lite.clock import (
    Clock,
    ClockChange,
    ClockType,
    JumpHandle,
    JumpThreshold,
    ROSClock,
    TimeJump,
)

__all__ = [
    'Clock',
    'ClockChange',
    'ClockType',
    'JumpHandle',
    'JumpThreshold',
    'ROSClock',
    'TimeJump',
]
