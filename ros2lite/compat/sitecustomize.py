"""Started by Python itself in a ROS shell (``ros2lite env``): installs ros2lite's interface
import hook, then runs the ``sitecustomize`` this one shadows, if there is one.

Kept tiny and failure-proof: it runs at the start of every Python process of that shell.
"""

from __future__ import annotations

import importlib.machinery
import importlib.util
import os
import sys


def _reach_ros2lite() -> bool:
    """Make ``ros2lite`` importable: it normally is (same interpreter); another interpreter of
    the same Python version finds it where ``ros2lite env`` said it lives."""
    if importlib.util.find_spec('ros2lite') is not None:
        return True
    version = f'{sys.version_info[0]}.{sys.version_info[1]}'
    if os.environ.get('ROS2LITE_PYTHON_VERSION') != version:
        return False
    for entry in os.environ.get('ROS2LITE_PYTHON_SITE', '').split(os.pathsep):
        if entry and entry not in sys.path:
            sys.path.append(entry)  # after this interpreter's own packages
    return importlib.util.find_spec('ros2lite') is not None


def _install_hook() -> None:
    if _reach_ros2lite():
        from ros2lite.msgs import install_top_level

        install_top_level()


def _chain() -> None:
    """Run the next ``sitecustomize`` on the path (e.g. Debian's), as if we were not here."""
    here = os.path.dirname(os.path.abspath(__file__))
    rest = [p for p in sys.path if os.path.abspath(p or os.curdir) != here]
    spec = importlib.machinery.PathFinder.find_spec('sitecustomize', rest)
    if spec is None or spec.loader is None:
        return
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)


try:
    _install_hook()
except Exception as e:  # never break the interpreter's start; say why once
    print(f'ros2lite env: interface import hook not installed: {e}', file=sys.stderr)
_chain()
