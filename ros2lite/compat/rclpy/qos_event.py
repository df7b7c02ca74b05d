"""rclpy.qos_event (the older name of rclpy.event_handler): the same names."""

from ros2lite.event_handler import *  # noqa: F403
from ros2lite.event_handler import __all__  # noqa: F401
