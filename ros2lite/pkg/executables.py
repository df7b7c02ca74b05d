"""What a package can run: the executables behind `ros2lite run`, `pkg executables` and
launch's `Node`.

The package comes from the package index (:mod:`ros2lite.pkg.index`, which says which source
owns a name); its executables depend on that source:

- a **source workspace** ament_python package: the ``console_scripts`` of its
  ``setup.py``/``setup.cfg`` (read, never executed), run straight from the sources;
- Python **entry points** in the group ``ros2lite.executables``, named
  ``<package>.<executable>`` (package names cannot contain a dot, so the first dot splits),
  e.g. in pyproject.toml::

       [project.entry-points."ros2lite.executables"]
       "my_pkg.talker" = "my_pkg.nodes:talker_main"

- an **ament prefix**: the executable files under ``lib/<package>`` — what ros2run looks at;
- the packages **bundled** with ros2lite (:data:`BUNDLED`, from :mod:`.bundled`).

Python targets are started as ``python -m ros2lite.pkg.runner <module:function> <name> …``
with the same interpreter, so they run in this environment without needing a console script
on PATH. Courses name a few C++ demo packages;
when one is not installed, :func:`resolve_executable` runs its Python twin
(:data:`EQUIVALENTS`) and says so, and :func:`equivalent` gives the twin to `pkg` and
`launch`. A workspace package that cannot run here says why in one line: the file colcon
would refuse (:class:`~ros2lite.pkg.errors.PackageFileError`), or that it is C++
(:mod:`.not_here`).
"""

from __future__ import annotations

import os
import re
import sys
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from importlib.machinery import PathFinder
from pathlib import Path

from ros2lite.exceptions import Ros2liteError

from .bundled import BUNDLED, STAND_INS
from .errors import NotHereError, PackageNotFoundError, did_you_mean
from .index import (
    ENTRY_POINT_GROUP,
    ORIGIN_AMENT,
    ORIGIN_BUNDLED,
    ORIGIN_ENTRY_POINT,
    ORIGIN_WORKSPACE,
    Package,
    PackageIndex,
)
from .not_here import cpp_executable_line, cpp_package_line, cpp_sources

__all__ = [
    'EQUIVALENTS',
    'ExecutableNotFoundError',
    'MultipleExecutablesError',
    'PackageExecutable',
    'PackageNotFoundError',
    'Resolved',
    'equivalent',
    'equivalent_executables',
    'find_executable',
    'get_executables',
    'list_packages',
    'package_executables',
    'resolve_executable',
]

RUNNER = 'ros2lite.pkg.runner'
_PYTHON = re.compile(r'python[0-9.]*\Z')

# C++ packages that courses run, and the bundled Python package that does the same thing under
# the same executable names (used only when the C++ package itself is not installed)
EQUIVALENTS = {'demo_nodes_cpp': 'demo_nodes_py'}


class ExecutableNotFoundError(Ros2liteError, LookupError):
    """The package has no executable by that name; the message names close matches (or,
    given, says why it is not here)."""

    def __init__(
        self, package: str, name: str, known: Sequence[str] = (), message: str | None = None
    ) -> None:
        super().__init__(message or f'No executable found{did_you_mean(name, known)}')
        self.package = package
        self.name = name


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
    target: str  # 'module:attr' for Python ones, a file path for ament
    origin: str  # 'workspace', 'entry point', 'ament' or 'bundled'
    pythonpath: tuple[str, ...] = ()  # where its modules are, for sources run in place

    @property
    def is_python(self) -> bool:
        """Whether it is run with a Python interpreter (not an ament file)."""
        return self.origin != ORIGIN_AMENT

    def command(self, argv: Sequence[str] = (), python: str | None = None) -> list[str]:
        """The argv that starts it; `argv` is passed through untouched (`--ros-args` too).
        A Python target runs through :mod:`ros2lite.pkg.runner` with this interpreter."""
        if not self.is_python:
            return [self.target, *argv]
        return [python or sys.executable, *self.python_arguments(argv)]

    def python_arguments(self, argv: Sequence[str] = ()) -> list[str]:
        """What follows the interpreter for a Python target (for a prefix such as
        `python -m pdb`, which brings its own interpreter)."""
        return ['-m', RUNNER, self.target, self.name, *argv]

    def prefixed_command(self, prefix: Sequence[str], argv: Sequence[str] = ()) -> list[str]:
        """The command under a prefix (`gdb -ex run --args`, `valgrind`, …). A prefix that
        is itself a Python interpreter (`python -m pdb`) runs a Python target directly."""
        if self.is_python and prefix and _PYTHON.match(os.path.basename(prefix[0])):
            return [*prefix, *self.python_arguments(argv)]
        return [*prefix, *self.command(argv)]

    def path(self) -> str:
        """A file to show for it (`pkg executables --full-path`): the file itself, or the
        module that holds a Python target (found without importing anything)."""
        if not self.is_python:
            return self.target
        module = self.target.partition(':')[0]
        found = _module_file(module, self.pythonpath)
        return found if found is not None else self.target


def _module_file(module: str, pythonpath: Sequence[str]) -> str | None:

    search: list[str] | None = [*pythonpath, *sys.path]
    spec = None
    parts = module.split('.')
    for i in range(len(parts)):
        spec = PathFinder.find_spec('.'.join(parts[: i + 1]), search)
        if spec is None:
            return None
        search = list(spec.submodule_search_locations or [])
    return spec.origin if spec is not None else None


# -- each source's executables -----------------------------------------------------------------


def _workspace_executables(pkg: Package) -> list[PackageExecutable]:
    """An ament_python package's console scripts, run from its sources (its setup.py or
    setup.cfg broken: the first problem, raised); an ament_cmake package with C++ sources
    is not here (NotHereError); other build types need a build before anything can run."""
    source = pkg.source
    if source is None:
        return []
    if source.manifest.build_type == 'ament_cmake':
        sources = cpp_sources(source.directory)
        if sources:
            raise NotHereError(pkg.name, cpp_package_line(pkg.name, source.directory, sources))
        return []
    if source.manifest.build_type != 'ament_python':
        return []
    from .setup_files import read_python_package  # ast + configparser: workspaces only

    info = read_python_package(source.directory)
    if info.problems:
        raise info.problems[0]
    root = str(info.package_root or source.directory)
    return [
        PackageExecutable(pkg.name, name, target, ORIGIN_WORKSPACE, (root,))
        for name, target in sorted(info.console_scripts.items())
    ]


def _entry_point_executables(package: str) -> list[PackageExecutable]:
    from importlib.metadata import entry_points

    found = []
    for ep in entry_points(group=ENTRY_POINT_GROUP):
        name, dot, exe = ep.name.partition('.')
        if dot and name == package and exe:
            found.append(
                PackageExecutable(package, exe, f'{ep.module}:{ep.attr}', ORIGIN_ENTRY_POINT)
            )
    return sorted(found, key=lambda e: e.name)


def _ament_executables(package: str, prefix: Path) -> list[PackageExecutable]:
    """PackageExecutable files under `<prefix>/lib/<package>`, skipping hidden directories."""
    found = []
    for dirpath, dirnames, filenames in os.walk(prefix / 'lib' / package):
        dirnames[:] = sorted(d for d in dirnames if not d.startswith('.'))
        for filename in sorted(filenames):
            path = os.path.join(dirpath, filename)
            if os.access(path, os.X_OK):
                found.append(PackageExecutable(package, filename, path, ORIGIN_AMENT))
    return sorted(found, key=lambda e: e.target)


def _bundled(package: str) -> list[PackageExecutable]:
    return [
        PackageExecutable(package, name, target, ORIGIN_BUNDLED)
        for name, target in sorted(BUNDLED.get(package, {}).items())
    ]


def package_executables(pkg: Package) -> list[PackageExecutable]:
    """Everything `pkg` can run, as its source defines it."""
    if pkg.origin == ORIGIN_WORKSPACE:
        return _workspace_executables(pkg)
    if pkg.origin == ORIGIN_ENTRY_POINT:
        return _entry_point_executables(pkg.name)
    if pkg.origin == ORIGIN_AMENT:
        return _ament_executables(pkg.name, pkg.prefix)
    if pkg.origin == ORIGIN_BUNDLED:
        return _bundled(pkg.name)
    return []


# -- queries ------------------------------------------------------------------------------------


def _index(env: Mapping[str, str] | None, index: PackageIndex | None) -> PackageIndex:
    return index if index is not None else PackageIndex(env)


def get_executables(
    package: str, env: Mapping[str, str] | None = None, *, index: PackageIndex | None = None
) -> list[PackageExecutable]:
    """All executables of `package` from the first source that has it."""
    idx = _index(env, index)
    pkg = idx.find(package)
    if pkg is None:
        raise idx.not_found(package)
    return package_executables(pkg)


def equivalent(package: str, index: PackageIndex) -> Package | None:
    """The Python twin that stands in for `package` (a C++ demo package no source
    provides), or None."""
    twin = EQUIVALENTS.get(package)
    if twin is None or index.find(package) is not None:
        return None
    return index.find(twin)


def equivalent_executables(package: str, index: PackageIndex) -> list[PackageExecutable]:
    """What `run <package> …` runs for a C++ demo package that is not installed: its twin's
    executables and, while the twin is the bundled one (not a package shadowing it), the
    stand-ins for the ones only the C++ package has, by name."""
    twin = equivalent(package, index)
    if twin is None:
        return []
    found = {e.name: e for e in package_executables(twin)}
    stand_ins = STAND_INS.get(twin.name, {}) if twin.origin == ORIGIN_BUNDLED else {}
    for name, target in stand_ins.items():
        found.setdefault(name, PackageExecutable(twin.name, name, target, ORIGIN_BUNDLED))
    return [found[name] for name in sorted(found)]


def find_executable(
    package: str,
    name: str,
    env: Mapping[str, str] | None = None,
    *,
    index: PackageIndex | None = None,
) -> PackageExecutable | None:
    """The executable `name` of `package`; None when the package has none by that name.

    Raises PackageNotFoundError, or MultipleExecutablesError when an ament package has several
    files with that name in different subdirectories.
    """
    matches = [e for e in get_executables(package, env, index=index) if e.name == name]
    if len(matches) > 1:
        raise MultipleExecutablesError([e.target for e in matches])
    return matches[0] if matches else None


@dataclass(frozen=True)
class Resolved:
    """An executable to start, and a line to tell the user when it is a stand-in."""

    executable: PackageExecutable
    note: str | None = None


def resolve_executable(
    package: str,
    name: str,
    env: Mapping[str, str] | None = None,
    *,
    index: PackageIndex | None = None,
) -> Resolved:
    """What `run <package> <name>` (or a launch `Node`) starts.

    A package in :data:`EQUIVALENTS` that no source provides runs its Python twin, with a
    note saying so. Raises PackageNotFoundError / ExecutableNotFoundError (naming close
    matches) or MultipleExecutablesError.
    """
    idx = _index(env, index)
    twin = equivalent(package, idx)
    if twin is not None:
        standing_in = {e.name: e for e in equivalent_executables(package, idx)}
        exe = standing_in.get(name)
        if exe is not None:
            if name not in STAND_INS.get(twin.name, {}) or twin.origin != ORIGIN_BUNDLED:
                note = f'running {twin.name} {name}, its Python equivalent'
            else:
                note = f'running a Python {name} bundled with ros2lite'
            return Resolved(exe, f'{package} (C++) is not installed; {note}')
        why = cpp_executable_line(package, name)
        raise ExecutableNotFoundError(package, name, list(standing_in), message=why)
    exe = find_executable(package, name, index=idx)
    if exe is None:
        known = [e.name for e in get_executables(package, index=idx)]
        raise ExecutableNotFoundError(package, name, known)
    return Resolved(exe)


def list_packages(env: Mapping[str, str] | None = None) -> list[str]:
    """Every package the index knows, sorted."""
    return list(PackageIndex(env).packages())
