"""`launch.conditions`: ros2lite's conditions under launch's names."""

from ros2lite.launch.conditions import *  # noqa: F403
from ros2lite.launch.conditions import __all__  # noqa: F401
