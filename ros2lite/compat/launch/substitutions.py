"""`launch.substitutions`: ros2lite's substitutions under launch's names."""

from ros2lite.launch.substitutions import *  # noqa: F403
from ros2lite.launch.substitutions import __all__  # noqa: F401
