"""`launch.events.process`: process events under launch's names (ros2lite keeps every
launch event in ros2lite.launch.events)."""

from ros2lite.launch.events import *  # noqa: F403
from ros2lite.launch.events import __all__  # noqa: F401
