"""rclpy.event_handler: the names of :mod:`ros2lite.event_handler`, which is rclpy-shaped."""

from ros2lite.event_handler import *  # noqa: F403
from ros2lite.event_handler import __all__  # noqa: F401
