"""Environments: what makes a shell (or a child process) a ROS shell, and the environment of a
process started from the package index (`run`, launch's `Node`).

A ROS shell is ros2lite's counterpart of sourcing `/opt/ros/jazzy/setup.bash`. The compat
directory (``ros2lite/compat``) goes first on ``PYTHONPATH``. It holds the faces that code
written for ROS imports by their ROS names (the package ``rclpy``; each further face, such as
``launch``, is one more directory there) and a ``sitecustomize`` that installs the interface
import hook (:func:`ros2lite.msgs.install_top_level`), so ``from std_msgs.msg import String``
works for every interface package ros2lite finds. Nothing named after a ROS package is ever
installed into site-packages: without this environment, a real ROS install on the same machine
is never shadowed. ``ros2lite env`` prints :func:`shell_lines` for the user's shell.

A child started from the package index gets three things on top of the caller's environment
(:func:`child_environment`):

- what ``ros2lite env`` gives a shell (:func:`ros_environment`): the compat
  directory first on ``PYTHONPATH``, so code written for ROS imports ``rclpy``, ``launch``,
  ``launch_ros``, ``ament_index_python`` and interface packages by their ROS names, and the
  scripts directory of ros2lite's environment last on ``PATH`` (``xacro``);
- the executable's own source directory (a workspace package run in place), so
  ``py_pubsub.publisher_member_function`` imports without an install;
- ``ROS2LITE_WORKSPACE`` naming the workspaces this process saw, so the child finds the same
  packages and interfaces even when it runs in another directory.
"""

from __future__ import annotations

import os
import shlex
import sys
import sysconfig
from collections.abc import Iterable, Mapping
from pathlib import Path

from ros2lite.exceptions import Ros2liteError

from .workspace import WORKSPACE_ENV

__all__ = [
    'COMPAT_DIR',
    'SHELLS',
    'UnknownShellError',
    'child_environment',
    'prepend_path',
    'ros_environment',
    'shell_lines',
]

COMPAT_DIR = Path(__file__).resolve().parents[1] / 'compat'
SHELLS = ('bash', 'zsh', 'fish')

# for an interpreter other than ros2lite's own (e.g. /usr/bin/python3 while ros2lite lives in
# a pipx venv): where ros2lite and its dependencies are, and for which Python version, so the
# compat sitecustomize can reach them when that version matches
SITE_VAR = 'ROS2LITE_PYTHON_SITE'
VERSION_VAR = 'ROS2LITE_PYTHON_VERSION'
CHECK_FIELDS_VAR = 'ROS_PYTHON_CHECK_FIELDS'


class UnknownShellError(Ros2liteError, ValueError):
    """A shell we cannot write lines for."""


def _python_site() -> list[str]:
    """Directories this interpreter imports ros2lite and its dependencies from."""
    dirs = [str(Path(__file__).resolve().parents[2])]
    paths = sysconfig.get_paths()
    for key in ('purelib', 'platlib'):
        if paths.get(key) and paths[key] not in dirs:
            dirs.append(paths[key])
    return dirs


def ros_environment(base: Mapping[str, str] | None = None) -> dict[str, str]:
    """The variables to set (name → value) on top of `base` (default: this process's
    environment). Applying them twice changes nothing: the compat directory is moved to the
    front of ``PYTHONPATH``, never added again."""
    env = os.environ if base is None else base
    compat = str(COMPAT_DIR)
    rest = [p for p in env.get('PYTHONPATH', '').split(os.pathsep) if p and p != compat]
    changes = {
        'PYTHONPATH': os.pathsep.join([compat, *rest]),
        SITE_VAR: os.pathsep.join(_python_site()),
        VERSION_VAR: f'{sys.version_info[0]}.{sys.version_info[1]}',
    }
    # the scripts of ros2lite's own environment (its dependencies' `xacro`, for launch files'
    # `Command(['xacro ', path])`) last on PATH: found where nothing else is, so a real ROS
    # install's programs, and the user's own, still come first
    scripts = sysconfig.get_paths().get('scripts')
    path = env.get('PATH', '')
    if scripts and scripts not in path.split(os.pathsep):
        changes['PATH'] = os.pathsep.join([p for p in (path, scripts) if p])
    # Jazzy's message classes check field assignments only when asked to (=1); ros2lite's
    # check unless told not to (=0): a ROS shell gets Jazzy's default unless it chose
    if CHECK_FIELDS_VAR not in env:
        changes[CHECK_FIELDS_VAR] = '0'
    return changes


def shell_lines(
    shell: str = 'bash',
    base: Mapping[str, str] | None = None,
    *,
    workspaces: Iterable[Path] = (),
) -> str:
    """Lines that `eval` in `shell` turns into :func:`ros_environment` (values quoted).

    `workspaces` (the ones the shell stands in, see :func:`ros2lite.pkg.workspace.workspaces`)
    go in front of ``ROS2LITE_WORKSPACE``: a shell that evaluates these lines somewhere else
    (another terminal, ``cd ~`` afterwards) still finds their packages and interfaces, as a
    shell that sourced ``install/setup.bash`` does on ROS."""
    if shell not in SHELLS:
        raise UnknownShellError(f"unknown shell '{shell}'; choose one of: {', '.join(SHELLS)}")
    env = os.environ if base is None else base
    changes = ros_environment(env)
    known = [str(ws) for ws in workspaces]
    if known:
        changes[WORKSPACE_ENV] = prepend_path(env.get(WORKSPACE_ENV, ''), known)
    lines = []
    for name, value in changes.items():
        if shell == 'fish':
            # fish splits *PATH variables on ':' itself; one quoted word keeps the others whole
            lines.append(f'set -gx {name} {_fish_quote(value)};')
        else:
            lines.append(f'export {name}={shlex.quote(value)};')
    return '\n'.join(lines) + '\n'


def _fish_quote(value: str) -> str:
    """A fish single-quoted word: only backslash and the quote itself need escaping."""
    return "'" + value.replace('\\', '\\\\').replace("'", "\\'") + "'"


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
