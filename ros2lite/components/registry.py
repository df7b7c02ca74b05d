"""Where components (node classes a container loads by name) are found.

A component is named as in ROS: a package and a plugin name (`composition` +
`composition::Talker`). Sources, searched in this order; the first that knows a *package*
owns it (as for executables, a package is never merged from two places):

1. Python entry points in the group ``ros2lite.components``, named ``<package>.<plugin>``
   (package names have no dot, so the first dot splits), e.g. in pyproject.toml::

       [project.entry-points."ros2lite.components"]
       "my_pkg.my_pkg::Talker" = "my_pkg.talker:Talker"

2. ament prefixes on ``AMENT_PREFIX_PATH``: the resource index type ``rclpy_components``
   (lines ``<plugin>;<module>:<Class>``, Python classes a ROS workspace installs) and
   ``rclcpp_components`` (lines ``<plugin>;<library>``: C++ components, which only rclcpp's
   container can load — they are listed, and refused by ours with a reason).
3. The components bundled with ros2lite (:data:`BUNDLED`: the composition demo's).

A Python component is a class whose constructor takes a node's keyword arguments
(``context``, ``cli_args``, ``parameter_overrides``, ``use_global_arguments``…) and builds a
:class:`ros2lite.node.Node` — name and namespace come through ``cli_args`` remaps, as
rclcpp's NodeOptions carry them.
"""

from __future__ import annotations

import importlib
import os
import sys
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from pathlib import Path

from ros2lite.exceptions import Ros2liteError
from ros2lite.util.files import ReadRefused, read_bounded

__all__ = [
    'BUNDLED',
    'ENTRY_POINT_GROUP',
    'ComponentLoadError',
    'ComponentType',
    'component_types',
    'find_component',
    'load_class',
]

ENTRY_POINT_GROUP = 'ros2lite.components'
PYTHON_RESOURCE = 'rclpy_components'
CPP_RESOURCE = 'rclcpp_components'

BUNDLED: dict[str, dict[str, str]] = {
    'composition': {
        'composition::Talker': 'ros2lite.bundled.composition.talker:Talker',
        'composition::Listener': 'ros2lite.bundled.composition.listener:Listener',
        'composition::Server': 'ros2lite.bundled.composition.server:Server',
        'composition::Client': 'ros2lite.bundled.composition.client:Client',
    }
}

ORIGIN_ENTRY_POINT = 'entry point'
ORIGIN_AMENT_PYTHON = 'ament python'
ORIGIN_AMENT_CPP = 'ament C++'
ORIGIN_BUNDLED = 'bundled'

# what rclcpp's container answers, so scripts written against it keep working
UNKNOWN_PACKAGE = 'Could not find requested resource in ament index'
UNKNOWN_PLUGIN = 'Failed to find class with the requested plugin name.'


class ComponentLoadError(Ros2liteError, LookupError):
    """A component cannot be found or loaded; the message is what the container answers."""


@dataclass(frozen=True)
class ComponentType:
    """One loadable component: a Python `module:Class`, or a C++ library (listed only)."""

    package: str
    plugin: str
    target: str
    origin: str
    prefix: Path | None = None  # the ament prefix it came from

    @property
    def is_python(self) -> bool:
        """Whether ros2lite's container can load it (a Python class, not a C++ plugin)."""
        return self.origin != ORIGIN_AMENT_CPP


def _entry_point_types() -> dict[str, list[ComponentType]]:
    from importlib.metadata import entry_points

    found: dict[str, list[ComponentType]] = {}
    for ep in entry_points(group=ENTRY_POINT_GROUP):
        package, dot, plugin = ep.name.partition('.')
        if not dot or not package or not plugin:
            continue  # malformed name: ignore rather than break every container
        found.setdefault(package, []).append(
            ComponentType(package, plugin, f'{ep.module}:{ep.attr}', ORIGIN_ENTRY_POINT)
        )
    return found


def _ament_types(env: Mapping[str, str] | None) -> dict[str, list[ComponentType]]:
    """Components registered in the ament resource index of every prefix, first prefix
    first (a package in an overlay hides the same package underneath)."""
    from ros2lite.pkg.index import ament_prefixes

    found: dict[str, list[ComponentType]] = {}
    for prefix in ament_prefixes(env):
        for resource, origin in (
            (PYTHON_RESOURCE, ORIGIN_AMENT_PYTHON),
            (CPP_RESOURCE, ORIGIN_AMENT_CPP),
        ):
            index = prefix / 'share' / 'ament_index' / 'resource_index' / resource
            if not index.is_dir():
                continue
            for entry in sorted(index.iterdir()):
                if entry.name.startswith('.') or not entry.is_file() or entry.name in found:
                    continue
                found[entry.name] = _read_resource(entry, origin, prefix)
    return found


# a resource index entry names a few plugins a line
_RESOURCE_LIMIT = 1024 * 1024


def _read_resource(path: Path, origin: str, prefix: Path) -> list[ComponentType]:
    """`<plugin>;<target>` lines (blank and malformed lines skipped)."""
    try:
        data = read_bounded(path, _RESOURCE_LIMIT, ReadRefused, 'a resource index entry')
    except ReadRefused:
        return []
    types = []
    for line in data.decode('utf-8', 'replace').splitlines():
        plugin, sep, target = line.partition(';')
        plugin, target = plugin.strip(), target.strip()
        if sep and plugin and target:
            types.append(ComponentType(path.name, plugin, target, origin, prefix))
    return types


def _bundled_types() -> dict[str, list[ComponentType]]:
    return {
        package: [ComponentType(package, p, t, ORIGIN_BUNDLED) for p, t in plugins.items()]
        for package, plugins in BUNDLED.items()
    }


def component_types(env: Mapping[str, str] | None = None) -> dict[str, list[ComponentType]]:
    """Every package with components and its components, packages sorted by name, each
    package from the first source that has it."""
    merged: dict[str, list[ComponentType]] = {}
    for source in (_entry_point_types(), _ament_types(env), _bundled_types()):
        for package, types in source.items():
            merged.setdefault(package, types)
    return dict(sorted(merged.items()))


def find_component(
    package: str, plugin: str, env: Mapping[str, str] | None = None
) -> ComponentType:
    """The component `plugin` of `package`; ComponentLoadError with rclcpp's words if
    either is unknown."""
    types = component_types(env).get(package)
    if types is None:
        raise ComponentLoadError(UNKNOWN_PACKAGE)
    for found in types:
        if found.plugin == plugin:
            return found
    raise ComponentLoadError(UNKNOWN_PLUGIN)


def load_class(component: ComponentType) -> Callable[..., object]:
    """Import the component's class; ComponentLoadError saying why it cannot be."""
    if not component.is_python:
        raise ComponentLoadError(
            f"'{component.plugin}' is a C++ component ({component.target}): ros2lite's "
            "container loads Python classes only; load it into rclcpp_components' container"
        )
    module_name, _, attr = component.target.partition(':')
    if not module_name or not attr:
        raise ComponentLoadError(
            f"'{component.plugin}' is registered as '{component.target}', not 'module:Class'"
        )
    if component.prefix is not None:
        _add_python_path(component.prefix)
    try:
        found: object = importlib.import_module(module_name)
        for part in attr.split('.'):
            found = getattr(found, part)
    except Exception as e:  # the module's own import errors too: report, never crash
        raise ComponentLoadError(
            f"cannot import '{component.target}' for '{component.plugin}': {type(e).__name__}: {e}"
        ) from None
    if not callable(found):
        raise ComponentLoadError(f"'{component.target}' is not a class")
    return found


def _add_python_path(prefix: Path) -> None:
    """Make an ament prefix's Python packages importable (what sourcing its setup file
    does), for a container started before the workspace was sourced."""
    version = f'python{sys.version_info.major}.{sys.version_info.minor}'
    for candidate in (
        prefix / 'lib' / version / 'site-packages',
        prefix / 'local' / 'lib' / version / 'dist-packages',
    ):
        path = os.fspath(candidate)
        if candidate.is_dir() and path not in sys.path:
            sys.path.append(path)
