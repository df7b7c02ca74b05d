"""rclpy.logging: this module *is* :mod:`ros2lite.logging` (assigning `_root_logger` here,
as some code does, reaches the library's loggers)."""

import sys

import ros2lite.logging

sys.modules[__name__] = ros2lite.logging
