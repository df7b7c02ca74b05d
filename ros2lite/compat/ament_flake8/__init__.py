"""`ament_flake8`, as the tests `ros2 pkg create` writes import it (`main_with_errors`).

PyPI's ament-lint-flake8 pins flake8 4.0.1, which cannot load its plugins on Python 3.12 and
later; there ros2lite's colcon extra brings a current flake8 and this face runs it with ROS's
settings. Where a real ament_flake8 is installed (the wheel, or a sourced ROS install), this
package steps aside: its modules are then that one's.
"""

import importlib.machinery
import os
import sys


def _real_package() -> list[str] | None:
    """The folder of an ament_flake8 further down sys.path, if there is one."""
    compat = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    rest = [p for p in sys.path if os.path.abspath(p or os.curdir) != compat]
    spec = importlib.machinery.PathFinder.find_spec(__name__, rest)
    if spec is None or not spec.submodule_search_locations:
        return None
    return list(spec.submodule_search_locations)


if __name__ == 'ament_flake8':  # imported by its ROS name, not as ros2lite.compat.ament_flake8
    _real = _real_package()
    if _real:
        __path__[:] = _real
