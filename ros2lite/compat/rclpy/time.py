"""rclpy.time (which also hands out Duration: tf2's tutorials write `rclpy.time.Duration`)."""

from ros2lite.duration import Duration
from ros2lite.time import Time

__all__ = ['Duration', 'Time']
