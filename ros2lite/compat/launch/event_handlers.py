"""`launch.event_handlers`: ros2lite's event handlers under launch's names."""

from ros2lite.launch.event_handlers import *  # noqa: F403
from ros2lite.launch.event_handlers import __all__  # noqa: F401
