"""What makes a shell (or a child process) a ROS shell: ros2lite's counterpart of sourcing
`/opt/ros/jazzy/setup.bash`.

The compat directory (``ros2lite/compat``) goes first on ``PYTHONPATH``. It holds the faces
that code written for ROS imports by their ROS names (the package ``rclpy``; each further face,
such as ``launch``, is one more directory there) and a ``sitecustomize`` that installs the
interface import hook (:func:`ros2lite.msgs.install_top_level`), so ``from std_msgs.msg import
String`` works for every interface package ros2lite finds. Nothing named after a ROS package is
ever installed into site-packages: without this environment, a real ROS install on the same
machine is never shadowed.

``ros2lite env`` prints :func:`shell_lines` for the user's shell; ``ros2lite run`` gives its
children :func:`ros_environment` directly.
"""

from __future__ import annotations

import os
import shlex
import sys
import sysconfig
from collections.abc import Mapping
from pathlib import Path

from ros2lite.exceptions import Ros2liteError

__all__ = ['COMPAT_DIR', 'SHELLS', 'UnknownShellError', 'ros_environment', 'shell_lines']

COMPAT_DIR = Path(__file__).resolve().parent / 'compat'
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
    dirs = [str(Path(__file__).resolve().parent.parent)]
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
    # Jazzy's message classes check field assignments only when asked to (=1); ros2lite's
    # check unless told not to (=0): a ROS shell gets Jazzy's default unless it chose
    if CHECK_FIELDS_VAR not in env:
        changes[CHECK_FIELDS_VAR] = '0'
    return changes


def shell_lines(shell: str = 'bash', base: Mapping[str, str] | None = None) -> str:
    """Lines that `eval` in `shell` turns into :func:`ros_environment` (values quoted)."""
    if shell not in SHELLS:
        raise UnknownShellError(f"unknown shell '{shell}'; choose one of: {', '.join(SHELLS)}")
    lines = []
    for name, value in ros_environment(base).items():
        if shell == 'fish':
            # fish splits *PATH variables on ':' itself; one quoted word keeps the others whole
            lines.append(f'set -gx {name} {_fish_quote(value)};')
        else:
            lines.append(f'export {name}={shlex.quote(value)};')
    return '\n'.join(lines) + '\n'


def _fish_quote(value: str) -> str:
    """A fish single-quoted word: only backslash and the quote itself need escaping."""
    return "'" + value.replace('\\', '\\\\').replace("'", "\\'") + "'"
