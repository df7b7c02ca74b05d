"""`ament_index_python.packages` over ros2lite's package index."""

from ros2lite.pkg.ament_index import *  # noqa: F403
from ros2lite.pkg.ament_index import __all__  # noqa: F401
