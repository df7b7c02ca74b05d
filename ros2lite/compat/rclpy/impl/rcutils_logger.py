"""rclpy.impl.rcutils_logger."""

from ros2lite.logging import RcutilsLogger

__all__ = ['RcutilsLogger']
