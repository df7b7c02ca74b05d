"""Where packages are found: the one package index.

Every part of ros2lite that looks for a package — `pkg`, `run`, `launch`, the type system,
shell completion — asks this module, so a prefix, a variable or a workspace is honoured the
same way everywhere.

Sources, first one first; **a package belongs entirely to the first source that knows it**
(as with ament overlays, nothing is merged from two places):

1. ``ROS2LITE_INTERFACE_PATH`` — directories of interface packages (`<pkg>/msg|srv|action`).
2. **Source workspaces** (:mod:`ros2lite.pkg.workspace`): the workspace enclosing the current
   directory, then each ``ROS2LITE_WORKSPACE`` entry — every `package.xml` under their `src/`.
   These come before installed packages so the code you are editing is the code that runs,
   even after an older `colcon build` of the same package was sourced.
3. Python entry points in the group ``ros2lite.executables`` (see :mod:`.executables`).
4. ``AMENT_PREFIX_PATH`` — a sourced ROS install or colcon `install/`: packages listed in each
   prefix's ament resource index, prefixes in order.
5. The Python environment's own prefix (:func:`environment_prefixes`), found with no variable
   set: interface packages that wheels such as ``ros-jazzy-std-msgs`` installed there (listed
   in its ament resource index, with `share/<pkg>/msg|srv|action`). They carry upstream's
   comments, which the bundled copies leave out. A name ros2lite bundles a demo for is not
   taken from here, so installing a ROS wheel never swaps a bundled node for a binary.
6. The packages bundled with ros2lite: its demos and its interface definitions.

`ros2lite pkg prefix <pkg>` prints where the winner lives and, when it is not an ament
prefix or when it shadows another source, a line on stderr naming the source.

A name no source knows is answered by :meth:`PackageIndex.not_found`, one line for every verb:
the broken file when a workspace package of that name could not be read; what to use instead
when ros2lite does not provide the package (:mod:`.not_here`); the ways in when a workspace
nearby holds it but this process does not use it; else close matches.
"""

from __future__ import annotations

import os
import site
import sys
import sysconfig
from collections.abc import Iterator, Mapping
from dataclasses import dataclass
from pathlib import Path

from .bundled import BUNDLED
from .errors import NotHereError, PackageFileError, PackageNotFoundError
from .manifest import MANIFEST, is_valid_package_name
from .not_here import not_here_line
from .workspace import (
    ROS2LITE_ROOT,
    SourcePackage,
    find_nearby,
    scan_workspace,
    workspace_sources,
    workspaces,
)

__all__ = [
    'BUNDLED_INTERFACES',
    'BUNDLED_PACKAGES',
    'ENTRY_POINT_GROUP',
    'INTERFACE_PATH_ENV',
    'ORIGINS',
    'Package',
    'PackageIndex',
    'ament_prefixes',
    'environment_prefixes',
    'interface_packages',
    'interface_roots',
]

INTERFACE_PATH_ENV = 'ROS2LITE_INTERFACE_PATH'
ENTRY_POINT_GROUP = 'ros2lite.executables'
"""The entry-point group whose `<package>.<executable>` names declare packages and executables."""
_ROOT = ROS2LITE_ROOT
BUNDLED_INTERFACES = _ROOT / 'msgs'
BUNDLED_PACKAGES = _ROOT / 'bundled'
_KINDS = ('msg', 'srv', 'action')
_AMENT_INDEX = Path('share') / 'ament_index' / 'resource_index' / 'packages'

ORIGIN_INTERFACE_PATH = 'interface path'
ORIGIN_WORKSPACE = 'workspace'
ORIGIN_ENTRY_POINT = 'entry point'
ORIGIN_AMENT = 'ament'
ORIGIN_ENVIRONMENT = 'environment'
ORIGIN_BUNDLED = 'bundled'
ORIGINS = (
    ORIGIN_INTERFACE_PATH,
    ORIGIN_WORKSPACE,
    ORIGIN_ENTRY_POINT,
    ORIGIN_AMENT,
    ORIGIN_ENVIRONMENT,
    ORIGIN_BUNDLED,
)


def _paths(value: str) -> list[Path]:
    return [Path(p) for p in value.split(os.pathsep) if p]


def ament_prefixes(env: Mapping[str, str] | None = None) -> list[Path]:
    """`AMENT_PREFIX_PATH`: a sourced ROS install or colcon workspace, first one first."""
    return _paths((os.environ if env is None else env).get('AMENT_PREFIX_PATH', ''))


_environment: list[Path] | None = None


def environment_prefixes() -> list[Path]:
    """The prefixes where pip puts this interpreter's data files (a wheel's
    `share/...`): the install scheme's data directory (a venv's root; Debian's /usr/local),
    `sys.prefix`, and the user base when user site-packages are on. Only those holding an
    ament resource index, so an environment without ROS wheels costs a few `stat`s, once."""
    global _environment
    if _environment is None:
        candidates = [sysconfig.get_path('data'), sys.prefix]
        if site.ENABLE_USER_SITE:
            # the user scheme's data directory is the user base; asking sysconfig for it fails
            # while `site` is still starting up (a sitecustomize importing a message package)
            candidates.append(site.getuserbase())
        found: list[Path] = []
        for candidate in candidates:
            prefix = Path(candidate)
            if prefix not in found and (prefix / _AMENT_INDEX).is_dir():
                found.append(prefix)
        _environment = found
    return list(_environment)


def interface_roots(env: Mapping[str, str] | None = None) -> list[Path]:
    """Directories whose children are interface packages (`<pkg>/msg|srv|action`), in
    priority order: `ROS2LITE_INTERFACE_PATH`, each ament prefix's `share/`, the Python
    environment's `share/`, the bundled set. (Source workspaces hold packages at any depth;
    :func:`interface_packages` has them.)"""
    environ = os.environ if env is None else env
    roots = _paths(environ.get(INTERFACE_PATH_ENV, ''))
    roots += [prefix / 'share' for prefix in ament_prefixes(environ)]
    roots += [prefix / 'share' for prefix in environment_prefixes()]
    roots.append(BUNDLED_INTERFACES)
    return roots


def _has_interfaces(path: Path) -> bool:
    return any((path / kind).is_dir() for kind in _KINDS)


@dataclass(frozen=True)
class Package:
    """One package as the index knows it."""

    name: str
    origin: str  # one of ORIGINS
    prefix: Path  # what `pkg prefix` prints
    share: Path | None = None  # package.xml, launch/, config/ live here
    interfaces: Path | None = None  # the directory holding msg/ srv/ action/
    source: SourcePackage | None = None  # set for workspace packages

    @property
    def manifest_path(self) -> Path | None:
        """Its package.xml, when it has one."""
        if self.share is not None and (self.share / MANIFEST).is_file():
            return self.share / MANIFEST
        return None

    def describe_source(self) -> str:
        """Where it came from, for people: 'source workspace /ws', 'ament prefix /opt/…'."""
        if self.origin == ORIGIN_WORKSPACE and self.source is not None:
            return f'source workspace {self.source.workspace}'
        if self.origin == ORIGIN_AMENT:
            return f'ament prefix {self.prefix}'
        if self.origin == ORIGIN_INTERFACE_PATH:
            return f'{INTERFACE_PATH_ENV} entry {self.prefix}'
        if self.origin == ORIGIN_ENTRY_POINT:
            return f'Python entry points installed in {self.prefix}'
        if self.origin == ORIGIN_ENVIRONMENT:
            return f'Python environment {self.prefix}'
        return 'packages bundled with ros2lite'


class PackageIndex:
    """The packages visible from one environment and working directory. Each source is
    read once, on first use, and then remembered: make a new index to see changes on disk
    (the module functions of :mod:`ros2lite.pkg` do, on every call)."""

    def __init__(self, env: Mapping[str, str] | None = None, cwd: Path | None = None) -> None:
        self.env: dict[str, str] = dict(os.environ if env is None else env)
        self.cwd = cwd
        self._sources: dict[str, dict[str, Package]] = {}
        self._workspaces: list[Path] | None = None
        self.problems: list[PackageFileError] = []
        self.broken: dict[str, PackageFileError] = {}

    # -- the sources, each name -> Package ---------------------------------------------------
    def workspaces(self) -> list[Path]:
        """The source workspaces in use, in priority order."""
        if self._workspaces is None:
            self._workspaces = workspaces(self.env, self.cwd)
        return self._workspaces

    def packages_from(self, origin: str) -> dict[str, Package]:
        """The packages one source (an ORIGIN_* name) provides, read once."""
        found = self._sources.get(origin)
        if found is None:
            reader = {
                ORIGIN_INTERFACE_PATH: self._read_interface_path,
                ORIGIN_WORKSPACE: self._read_workspaces,
                ORIGIN_ENTRY_POINT: self._read_entry_points,
                ORIGIN_AMENT: self._read_ament,
                ORIGIN_ENVIRONMENT: self._read_environment,
                ORIGIN_BUNDLED: self._read_bundled,
            }[origin]
            found = self._sources[origin] = reader()
        return found

    def _read_interface_path(self) -> dict[str, Package]:
        found: dict[str, Package] = {}
        for root in _paths(self.env.get(INTERFACE_PATH_ENV, '')):
            for child in _children(root):
                if child.name not in found and _has_interfaces(child):
                    found[child.name] = Package(
                        child.name, ORIGIN_INTERFACE_PATH, root, child, child
                    )
        return found

    def _read_workspaces(self) -> dict[str, Package]:
        found: dict[str, Package] = {}
        for ws in self.workspaces():
            scan = scan_workspace(workspace_sources(ws), ws)
            self.problems += scan.problems
            for name, problem in scan.broken.items():
                self.broken.setdefault(name, problem)
            for name, source in scan.packages.items():
                if name not in found:
                    d = source.directory
                    found[name] = Package(
                        name,
                        ORIGIN_WORKSPACE,
                        d,
                        d,
                        d if _has_interfaces(d) else None,
                        source,
                    )
        return found

    def _read_entry_points(self) -> dict[str, Package]:
        found: dict[str, Package] = {}
        if not _may_declare(ENTRY_POINT_GROUP):
            return found
        from importlib.metadata import entry_points

        for ep in entry_points(group=ENTRY_POINT_GROUP):
            package, dot, exe = ep.name.partition('.')
            if not dot or not exe or not is_valid_package_name(package) or package in found:
                continue
            dist = getattr(ep, 'dist', None)
            location = Path(str(dist.locate_file(''))) if dist is not None else Path()
            found[package] = Package(package, ORIGIN_ENTRY_POINT, location)
        return found

    def _read_ament(self) -> dict[str, Package]:
        found: dict[str, Package] = {}
        for prefix in ament_prefixes(self.env):
            names = [m.name for m in _children(prefix / _AMENT_INDEX) if m.is_file()]
            # interface definitions copied into a prefix count without an index marker
            names += [d.name for d in _children(prefix / 'share') if _has_interfaces(d)]
            for name in names:
                if name in found or not is_valid_package_name(name):
                    continue
                share = prefix / 'share' / name
                interfaces = share if _has_interfaces(share) else None
                found[name] = Package(name, ORIGIN_AMENT, prefix, share, interfaces)
        return found

    def _read_environment(self) -> dict[str, Package]:
        found: dict[str, Package] = {}
        for prefix in environment_prefixes():
            for marker in _children(prefix / _AMENT_INDEX):
                name = marker.name
                if name in found or name in BUNDLED or not is_valid_package_name(name):
                    continue
                share = prefix / 'share' / name
                if marker.is_file() and _has_interfaces(share):
                    found[name] = Package(name, ORIGIN_ENVIRONMENT, prefix, share, share)
        return found

    def _read_bundled(self) -> dict[str, Package]:
        found: dict[str, Package] = {}
        for child in _children(BUNDLED_INTERFACES):
            if _has_interfaces(child):
                found[child.name] = Package(child.name, ORIGIN_BUNDLED, _ROOT, child, child)
        for name in BUNDLED:
            demo = BUNDLED_PACKAGES / name
            interfaces = found[name].interfaces if name in found else None
            found[name] = Package(
                name, ORIGIN_BUNDLED, _ROOT, demo if demo.is_dir() else None, interfaces
            )
        return found

    # -- queries -----------------------------------------------------------------------------
    def candidates(self, name: str) -> list[Package]:
        """Every source's `name`, winner first (the rest are shadowed by it)."""
        return [pkg for origin in ORIGINS if (pkg := self.packages_from(origin).get(name))]

    def find(self, name: str) -> Package | None:
        """The package `name` from the first source that knows it."""
        for origin in ORIGINS:
            pkg = self.packages_from(origin).get(name)
            if pkg is not None:
                return pkg
        return None

    def not_found(self, name: str, message: str | None = None) -> PackageNotFoundError:
        """The error for a package no source knows (`message` replaces the first words,
        "Package 'x' not found", where a verb words it otherwise), with :meth:`why_missing`
        after them (asked when it is shown), else close matches."""
        base = message if message is not None else f"Package '{name}' not found"
        self.packages_from(ORIGIN_WORKSPACE)  # its broken packages
        if not_here_line(name) is not None and self.broken.get(name) is None:
            return NotHereError(name, f'{base}; {self.why_missing(name)}')
        return PackageNotFoundError(
            name, list(self.packages()), message=base, explain=lambda: self.why_missing(name)
        )

    def why_missing(self, name: str) -> str:
        """Why no source has `name`, or '' (when one has, or nothing explains it): the file
        and line that stopped a workspace package of that name from being read; what to use
        instead of a package ros2lite does not provide (:mod:`.not_here`); the ways into a
        workspace near the current directory that holds it, its sources unread by this
        process and its install/ not sourced."""
        if self.find(name) is not None:
            return ''
        broken = self.broken.get(name)
        if broken is not None:
            return str(broken)
        instead = not_here_line(name)
        if instead is not None:
            return instead
        try:
            here = (self.cwd if self.cwd is not None else Path.cwd()).absolute()
        except OSError:
            return ''
        nearby = find_nearby(name, here, self.workspaces())
        return nearby.ways_in() if nearby is not None else ''

    def packages(self) -> dict[str, Package]:
        """Every package (the winner for each name), sorted by name."""
        winners: dict[str, Package] = {}
        for origin in ORIGINS:
            for name, pkg in self.packages_from(origin).items():
                winners.setdefault(name, pkg)
        return dict(sorted(winners.items()))

    def interface_packages(self) -> dict[str, Path]:
        """Package name → the directory holding its msg/srv/action, for packages that have
        interfaces (owned, like everything, by the first source that knows the package).

        Entry points declare executables only: they neither have nor hide interfaces, and
        are not read here, which keeps every node's start-up free of a scan of all installed
        distributions."""
        found: dict[str, Path] = {}
        owned: set[str] = set()
        for origin in ORIGINS:
            if origin == ORIGIN_ENTRY_POINT:
                continue
            for name, pkg in self.packages_from(origin).items():
                if name not in owned:
                    owned.add(name)
                    if pkg.interfaces is not None:
                        found[name] = pkg.interfaces
        return dict(sorted(found.items()))


def _may_declare(group: str) -> bool:
    """Could an installed distribution declare entry points in `group`? A quick look at the
    entry_points.txt files on sys.path, so the common answer (none) costs no importlib.metadata
    scan of every distribution — that scan is what reads them properly when one may."""
    needle = f'[{group}]'.encode()
    for entry in sys.path:
        try:
            names = os.listdir(entry or '.')
        except OSError:
            continue
        for name in names:
            if name.endswith(('.dist-info', '.egg-info')):
                try:
                    with open(os.path.join(entry or '.', name, 'entry_points.txt'), 'rb') as f:
                        if needle in f.read():
                            return True
                except OSError:
                    continue
    return False


def _children(directory: Path) -> Iterator[Path]:
    try:
        return iter(sorted(directory.iterdir()))
    except OSError:
        return iter(())


def workspace_interface_packages(env: Mapping[str, str] | None = None) -> dict[str, Path]:
    """Package name → its interface directory, for the source workspaces' packages alone
    (the top-level import hook's quick "could this be an interface package?")."""
    index = PackageIndex(env)
    return {
        name: pkg.interfaces
        for name, pkg in index.packages_from(ORIGIN_WORKSPACE).items()
        if pkg.interfaces is not None
    }


def interface_packages(env: Mapping[str, str] | None = None) -> dict[str, Path]:
    """Package name → its interface directory, in the index's precedence."""
    return PackageIndex(env).interface_packages()
