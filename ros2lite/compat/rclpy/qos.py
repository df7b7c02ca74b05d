"""rclpy.qos: profiles, policies, presets and compatibility."""

from ros2lite.qos import *  # noqa: F403
from ros2lite.qos import __all__  # noqa: F401
