"""`ament_copyright`, as the tests `ros2 pkg create` writes import it (`ament_copyright.main`).

ROS's copyright and licence checker has no wheel on PyPI, so ros2lite carries one; it is on
PYTHONPATH in a ROS shell (`ros2lite env`) and in `colcon test` through ros2lite's plugin.
Where a real ament_copyright is installed (a sourced ROS install), this package steps aside:
its modules are then that one's.
"""

import importlib.machinery
import os
import sys


def _real_package() -> list[str] | None:
    """The folder of an ament_copyright further down sys.path, if there is one."""
    compat = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    rest = [p for p in sys.path if os.path.abspath(p or os.curdir) != compat]
    spec = importlib.machinery.PathFinder.find_spec(__name__, rest)
    if spec is None or not spec.submodule_search_locations:
        return None
    return list(spec.submodule_search_locations)


if __name__ == 'ament_copyright':  # imported by its ROS name, not as ros2lite.compat.*
    _real = _real_package()
    if _real:
        __path__[:] = _real
