"""`ament_index_python`, as launch files and nodes import it: package locations from
ros2lite's package index (source workspaces included)."""

from ros2lite.pkg.ament_index import *  # noqa: F403
from ros2lite.pkg.ament_index import __all__  # noqa: F401
