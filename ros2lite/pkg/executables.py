"""Where `ros2lite run <package> <executable>` finds what to start.

Three sources, searched in this order; the first one that knows a *package* owns it entirely
(as with ament overlays, a package is never merged from two places):

1. Python entry points in the group ``ros2lite.executables``, named ``<package>.<executable>``
   (package names cannot contain a dot, so the first dot splits), e.g. in pyproject.toml::

       [project.entry-points."ros2lite.executables"]
       "my_pkg.talker" = "my_pkg.nodes:talker_main"

2. ament prefixes on ``AMENT_PREFIX_PATH`` (a sourced ROS install or colcon workspace): the
   package is known when ``share/ament_index/resource_index/packages/<package>`` exists, and its
   executables are the executable files under ``lib/<package>`` — what ros2run looks at.
3. The packages bundled with ros2lite (:data:`BUNDLED`).

Python targets are started as ``python -c …`` with the same interpreter, so they run in this
environment without needing a console script on PATH.
"""

from __future__ import annotations

import os
import sys
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path

from ros2lite.exceptions import Ros2liteError
from ros2lite.pkg.index import ament_prefixes

ENTRY_POINT_GROUP = 'ros2lite.executables'

# the demos bundled with ros2lite: package -> executables, each `main()` of
# ros2lite.demos.<package>.<executable>
_DEMOS = {
    'action_tutorials_py': ['fibonacci_action_client', 'fibonacci_action_server'],
    'demo_nodes_py': [
        'add_two_ints_client',
        'add_two_ints_client_async',
        'add_two_ints_server',
        'introspection_client',
        'introspection_service',
        'listener',
        'parameter_blackboard',
        'talker',
    ],
    'lifecycle': ['lifecycle_listener'],
    'lifecycle_py': ['lifecycle_talker'],
    'rclpy_components': ['component_container', 'component_container_mt'],
    'rqt_graph': ['rqt_graph'],
    'teleop_twist_keyboard': ['teleop_twist_keyboard'],
    'turtlesim': ['draw_square', 'mimic', 'turtle_teleop_key', 'turtlesim_node'],
}
BUNDLED: dict[str, dict[str, str]] = {
    package: {name: f'ros2lite.demos.{package}.{name}:main' for name in names}
    for package, names in _DEMOS.items()
}

_ORIGIN_ENTRY_POINT = 'entry point'
_ORIGIN_AMENT = 'ament'
_ORIGIN_BUNDLED = 'bundled'


class PackageNotFoundError(Ros2liteError, LookupError):
    """No package of that name anywhere on the package path."""

    def __init__(self, package: str) -> None:
        super().__init__(f"Package '{package}' not found")
        self.package = package


class MultipleExecutablesError(Ros2liteError, LookupError):
    """More than one executable answers to the name (ros2cli's error)."""

    def __init__(self, locations: Sequence[str]) -> None:
        super().__init__('Multiple executables found:' + ''.join(f'\n- {p}' for p in locations))
        self.locations = list(locations)


@dataclass(frozen=True)
class PackageExecutable:
    """One runnable thing of a package: a Python `module:function` or a file."""

    package: str
    name: str
    target: str  # 'module:attr' for entry points and bundled ones, a file path for ament
    origin: str  # 'entry point', 'ament' or 'bundled'

    @property
    def is_python(self) -> bool:
        """Whether it is run with a Python interpreter (not an ament binary)."""
        return self.origin != _ORIGIN_AMENT

    def command(self, argv: Sequence[str] = (), python: str | None = None) -> list[str]:
        """The argv that starts it; `argv` is passed through untouched (`--ros-args` too)."""
        if not self.is_python:
            return [self.target, *argv]
        return [python or sys.executable, '-c', _python_launcher(self.target, self.name), *argv]


def _python_launcher(target: str, name: str) -> str:
    """Code for `python -c` that behaves like a console script: argv[0] is the executable's
    name, the working directory is not importable, and the return value is the exit status."""
    module, _, attr = target.partition(':')
    return (
        'import importlib, sys\n'
        "if sys.path and sys.path[0] in ('', '.'):\n"
        '    del sys.path[0]\n'
        f'sys.argv[0] = {name!r}\n'
        f'fn = importlib.import_module({module!r})\n'
        f'for part in {attr!r}.split("."):\n'
        '    fn = getattr(fn, part)\n'
        'sys.exit(fn())\n'
    )


# -- the three sources --------------------------------------------------------------------------


def _entry_point_packages() -> dict[str, list[PackageExecutable]]:
    from importlib.metadata import entry_points

    found: dict[str, list[PackageExecutable]] = {}
    for ep in entry_points(group=ENTRY_POINT_GROUP):
        package, dot, exe = ep.name.partition('.')
        if not dot or not package or not exe:
            continue  # malformed name: ignore rather than break every `run`
        found.setdefault(package, []).append(
            PackageExecutable(package, exe, f'{ep.module}:{ep.attr}', _ORIGIN_ENTRY_POINT)
        )
    return found


def _ament_prefix(package: str, prefixes: Iterable[Path]) -> Path | None:
    for prefix in prefixes:
        if (prefix / 'share' / 'ament_index' / 'resource_index' / 'packages' / package).is_file():
            return prefix
    return None


def _ament_executables(package: str, prefix: Path) -> list[PackageExecutable]:
    """PackageExecutable files under `<prefix>/lib/<package>`, skipping hidden directories."""
    found = []
    for dirpath, dirnames, filenames in os.walk(prefix / 'lib' / package):
        dirnames[:] = sorted(d for d in dirnames if not d.startswith('.'))
        for filename in sorted(filenames):
            path = os.path.join(dirpath, filename)
            if os.access(path, os.X_OK):
                found.append(PackageExecutable(package, filename, path, _ORIGIN_AMENT))
    return found


def _ament_packages(prefixes: Iterable[Path]) -> set[str]:
    names: set[str] = set()
    for prefix in prefixes:
        index = prefix / 'share' / 'ament_index' / 'resource_index' / 'packages'
        if index.is_dir():
            names.update(p.name for p in index.iterdir() if p.is_file())
    return names


def _bundled(package: str) -> list[PackageExecutable]:
    return [
        PackageExecutable(package, name, target, _ORIGIN_BUNDLED)
        for name, target in sorted(BUNDLED[package].items())
    ]


# -- queries ------------------------------------------------------------------------------------


def get_executables(package: str, env: Mapping[str, str] | None = None) -> list[PackageExecutable]:
    """All executables of `package` from the first source that has it."""
    entry = _entry_point_packages().get(package)
    if entry is not None:
        return sorted(entry, key=lambda e: e.name)
    prefix = _ament_prefix(package, ament_prefixes(env))
    if prefix is not None:
        return _ament_executables(package, prefix)
    if package in BUNDLED:
        return _bundled(package)
    raise PackageNotFoundError(package)


def find_executable(
    package: str, name: str, env: Mapping[str, str] | None = None
) -> PackageExecutable | None:
    """The executable `name` of `package`; None when the package has none by that name.

    Raises PackageNotFoundError, or MultipleExecutablesError when an ament package has several
    files with that name in different subdirectories.
    """
    matches = [e for e in get_executables(package, env) if e.name == name]
    if len(matches) > 1:
        raise MultipleExecutablesError([e.target for e in matches])
    return matches[0] if matches else None


def list_packages(env: Mapping[str, str] | None = None) -> list[str]:
    """Every package that has an entry here, sorted."""
    names = set(_entry_point_packages()) | _ament_packages(ament_prefixes(env)) | set(BUNDLED)
    return sorted(names)
