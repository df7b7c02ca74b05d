"""The environment of a process started from the package index (`run`, launch's `Node`).

Three things on top of the caller's environment:

- what ``ros2lite env`` gives a shell (:func:`ros2lite.env.ros_environment`): the compat
  directory first on ``PYTHONPATH``, so code written for ROS imports ``rclpy``, ``launch``,
  ``launch_ros``, ``ament_index_python`` and interface packages by their ROS names;
- the executable's own source directory (a workspace package run in place), so
  ``py_pubsub.publisher_member_function`` imports without an install;
- ``ROS2LITE_WORKSPACE`` naming the workspaces this process saw, so the child finds the same
  packages and interfaces even when it runs in another directory.
"""

from __future__ import annotations

import os
from collections.abc import Iterable, Mapping
from pathlib import Path

from ros2lite.env import COMPAT_DIR, ros_environment

from .workspace import WORKSPACE_ENV

__all__ = ['COMPAT_DIR', 'child_environment', 'prepend_path']


def prepend_path(value: str, entries: Iterable[str]) -> str:
    """`entries` in front of the `:`-separated `value`, each path once, order kept."""
    out: list[str] = []
    for entry in [*entries, *value.split(os.pathsep)]:
        if entry and entry not in out:
            out.append(entry)
    return os.pathsep.join(out)


def child_environment(
    base: Mapping[str, str] | None = None,
    *,
    pythonpath: Iterable[str] = (),
    workspaces: Iterable[Path] = (),
) -> dict[str, str]:
    """The whole environment for the child (see the module doc); `base` defaults to ours."""
    env = dict(os.environ if base is None else base)
    env.update(ros_environment(env))
    env['PYTHONPATH'] = prepend_path(env['PYTHONPATH'], [str(COMPAT_DIR), *pythonpath])
    known = [str(ws) for ws in workspaces]
    if known or env.get(WORKSPACE_ENV):
        env[WORKSPACE_ENV] = prepend_path(env.get(WORKSPACE_ENV, ''), known)
    return env
