"""Where packages are found: the one reading of the package search path.

Every part of ros2lite that looks for packages — the executables behind `run`, the interface
definitions behind the type system — starts from here, so a prefix, a variable or (later) a
source workspace is honoured the same way everywhere.
"""

from __future__ import annotations

import os
from collections.abc import Mapping
from pathlib import Path

__all__ = [
    'BUNDLED_INTERFACES',
    'INTERFACE_PATH_ENV',
    'ament_prefixes',
    'interface_roots',
]

INTERFACE_PATH_ENV = 'ROS2LITE_INTERFACE_PATH'
BUNDLED_INTERFACES = Path(__file__).resolve().parent.parent / 'msgs'


def _paths(value: str) -> list[Path]:
    return [Path(p) for p in value.split(os.pathsep) if p]


def ament_prefixes(env: Mapping[str, str] | None = None) -> list[Path]:
    """`AMENT_PREFIX_PATH`: a sourced ROS install or colcon workspace, first one first."""
    return _paths((os.environ if env is None else env).get('AMENT_PREFIX_PATH', ''))


def interface_roots(env: Mapping[str, str] | None = None) -> list[Path]:
    """Directories whose children are interface packages (`<pkg>/msg|srv|action`), in
    priority order: `ROS2LITE_INTERFACE_PATH`, each prefix's `share/`, the bundled set."""
    environ = os.environ if env is None else env
    roots = _paths(environ.get(INTERFACE_PATH_ENV, ''))
    roots += [prefix / 'share' for prefix in ament_prefixes(environ)]
    roots.append(BUNDLED_INTERFACES)
    return roots
