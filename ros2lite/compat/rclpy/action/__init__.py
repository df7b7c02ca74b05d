"""rclpy.action: action servers, clients and the graph queries, as :mod:`ros2lite.action`
offers them."""

from ros2lite.action import *  # noqa: F403
from ros2lite.action import __all__  # noqa: F401
