"""Source workspaces: packages straight from `src/`, with no build step.

A workspace is a directory whose `src/` holds packages (each a directory with a
`package.xml`, at any depth), as colcon sees it. ros2lite uses, in this order:

1. the workspace enclosing the current directory: the nearest of the current directory and
   its parents whose `src/` holds at least one package within four levels, and that looks
   like a workspace a user made for where they stand: it is the current directory itself,
   or the current directory lies inside its `src/`, or colcon has built there (its
   `build/`, `install/` or `log/` holds colcon's `COLCON_IGNORE`). A folder further up
   whose `src/` merely holds packages (a home directory's `~/src`) is not taken;
2. each directory in ``ROS2LITE_WORKSPACE`` (`:`-separated): its `src/` if it has one,
   else the directory itself.

ros2lite's own files are never a source workspace, nor part of one: its bundled packages
carry `package.xml` files (for `pkg xml`), and a checkout cloned into `~/ros2_ws/src/` (where
ROS users keep everything) would otherwise be read as a workspace of 40 packages hiding every
bundled demo. The walk skips the running ros2lite's package directory and any directory that
is a ros2lite package (another install or checkout, by its shape); the package directory also
holds a `COLCON_IGNORE`, so colcon itself skips it too.

The walk follows colcon's rules: it does not descend into a package, skips hidden
directories and any directory holding a `COLCON_IGNORE`, `AMENT_IGNORE` or `CATKIN_IGNORE`
file, follows symlinked directories once (no loops), and is bounded in depth and size so a
home directory with a huge `~/src` costs little. Within one workspace the first package found
by a name wins (colcon would refuse the duplicate; we say so in :attr:`Scan.problems`).
"""

from __future__ import annotations

import os
from collections.abc import Iterator, Mapping
from dataclasses import dataclass, field
from pathlib import Path

from .errors import PackageFileError
from .manifest import MANIFEST, Manifest, ManifestError, read_manifest

__all__ = [
    'IGNORE_MARKERS',
    'ROS2LITE_ROOT',
    'SKIPPED_DIRS',
    'WORKSPACE_ENV',
    'Nearby',
    'Scan',
    'SourcePackage',
    'enclosing_workspace',
    'find_nearby',
    'inside_ros2lite',
    'scan_workspace',
    'workspace_sources',
    'workspaces',
]

WORKSPACE_ENV = 'ROS2LITE_WORKSPACE'
IGNORE_MARKERS = ('COLCON_IGNORE', 'AMENT_IGNORE', 'CATKIN_IGNORE')
# never holding packages, and possibly huge
SKIPPED_DIRS = frozenset({'__pycache__', 'node_modules'})
_MAX_DEPTH = 8
_MAX_DIRS = 5000
# finding the enclosing workspace runs in every process that uses types: look less far
# (colcon workspaces keep packages at src/<repo>/<pkg>), so a big non-ROS ~/src costs little
_DETECT_DEPTH = 4
_DETECT_DIRS = 1000
ROS2LITE_ROOT = Path(__file__).resolve().parent.parent
"""The running ros2lite's package directory (its bundled packages and interfaces)."""
_own_key: tuple[int, int] | None = None


def _own_root_key() -> tuple[int, int]:
    global _own_key
    if _own_key is None:
        try:
            st = ROS2LITE_ROOT.stat()
            _own_key = (st.st_dev, st.st_ino)
        except OSError:
            _own_key = (-1, -1)
    return _own_key


def _is_ros2lite_package(directory: Path, names: set[str]) -> bool:
    """Is `directory` a ros2lite package directory (any install or checkout of it)?"""
    return (
        directory.name == 'ros2lite'
        and {'__init__.py', 'msgs', 'pkg'} <= names
        and (directory / 'pkg' / 'index.py').is_file()
    )


def inside_ros2lite(path: Path) -> bool:
    """Does `path` lie in the running ros2lite's package directory (never a workspace)?"""
    try:
        return path.resolve().is_relative_to(ROS2LITE_ROOT)
    except (OSError, RuntimeError):
        return False


@dataclass(frozen=True)
class SourcePackage:
    """A package found in a workspace's sources."""

    manifest: Manifest
    workspace: Path

    @property
    def name(self) -> str:
        """The package's name, from its package.xml."""
        return self.manifest.name

    @property
    def directory(self) -> Path:
        """The directory holding its package.xml."""
        return self.manifest.directory


@dataclass
class Scan:
    """The packages of one source tree, and what could not be read there (each problem is
    also kept under the package it most likely is: its name, else its directory's)."""

    root: Path
    packages: dict[str, SourcePackage] = field(default_factory=dict)
    problems: list[PackageFileError] = field(default_factory=list)
    broken: dict[str, PackageFileError] = field(default_factory=dict)

    def add_problem(self, problem: PackageFileError) -> None:
        """Keep a problem, and the first one per package name."""
        self.problems.append(problem)
        self.broken.setdefault(problem.package, problem)


def _package_dirs(
    root: Path, max_depth: int = _MAX_DEPTH, max_dirs: int = _MAX_DIRS
) -> Iterator[Path]:
    """Directories under `root` holding a package.xml, by colcon's walking rules."""
    seen: set[tuple[int, int]] = set()
    budget = max_dirs
    stack: list[tuple[Path, int]] = [(root, 0)]
    while stack and budget > 0:
        directory, depth = stack.pop()
        budget -= 1
        try:
            st = directory.stat()
            key = (st.st_dev, st.st_ino)
            if key in seen or key == _own_root_key():
                continue
            seen.add(key)
            entries = sorted(os.scandir(directory), key=lambda e: e.name)
        except OSError:
            continue
        names = {e.name for e in entries}
        if any(marker in names for marker in IGNORE_MARKERS):
            continue
        if _is_ros2lite_package(directory, names):
            continue
        if MANIFEST in names:  # a package (perhaps `src` itself): do not look inside
            yield directory
            continue
        if depth >= max_depth:
            continue
        children = [
            Path(e.path)
            for e in entries
            if not e.name.startswith('.') and e.name not in SKIPPED_DIRS and _is_dir(e)
        ]
        # reversed so the stack pops them in name order
        stack.extend((child, depth + 1) for child in reversed(children))


def _is_dir(entry: os.DirEntry[str]) -> bool:
    try:
        return entry.is_dir()  # follows a symlink; loops are caught by `seen`
    except OSError:
        return False


def scan_workspace(root: Path, workspace: Path | None = None) -> Scan:
    """Every package under `root` (a workspace's `src/`)."""
    scan = Scan(root)
    owner = workspace if workspace is not None else root
    if inside_ros2lite(root):
        return scan
    for directory in _package_dirs(root):
        try:
            manifest = read_manifest(directory / MANIFEST)
        except ManifestError as e:
            scan.add_problem(e)
            continue
        first = scan.packages.get(manifest.name)
        if first is not None:
            # not under `broken`: the name still has a package, the first one
            scan.problems.append(
                PackageFileError(
                    directory / MANIFEST,
                    None,
                    f"duplicate package '{manifest.name}' (using {first.directory})",
                    manifest.name,
                )
            )
            continue
        scan.packages[manifest.name] = SourcePackage(manifest, owner)
    return scan


def _has_package(src: Path) -> bool:
    return next(_package_dirs(src, _DETECT_DEPTH, _DETECT_DIRS), None) is not None


# what colcon leaves beside `src/` once it has built a workspace
_COLCON_BASES = ('build', 'install', 'log')


def _colcon_built(directory: Path) -> bool:
    return any((directory / base / 'COLCON_IGNORE').is_file() for base in _COLCON_BASES)


def enclosing_workspace(cwd: Path) -> Path | None:
    """The workspace the user stands in (see the module doc): the nearest of `cwd` and its
    parents whose `src/` holds a package, when it is `cwd`, holds `cwd` in its `src/`, or
    was built by colcon."""
    for directory in (cwd, *cwd.parents):
        src = directory / 'src'
        if not (directory == cwd or cwd.is_relative_to(src) or _colcon_built(directory)):
            continue
        if src.is_dir() and _has_package(src):
            return directory
    return None


def workspaces(env: Mapping[str, str] | None = None, cwd: Path | None = None) -> list[Path]:
    """The source workspaces in priority order (see the module doc), each once."""
    environ = os.environ if env is None else env
    try:
        here = Path.cwd() if cwd is None else cwd
    except OSError:  # the current directory was removed
        here = None
    found: list[Path] = []
    enclosing = enclosing_workspace(here.absolute()) if here is not None else None
    if enclosing is not None:
        found.append(enclosing)
    for entry in environ.get(WORKSPACE_ENV, '').split(os.pathsep):
        if entry and not inside_ros2lite(Path(entry).expanduser()):
            found.append(Path(entry).expanduser().absolute())
    unique: list[Path] = []
    keys: set[Path] = set()
    for ws in found:
        key = ws.resolve()
        if key not in keys:
            keys.add(key)
            unique.append(ws)
    return unique


def workspace_sources(workspace: Path) -> Path:
    """Where a workspace's packages are: its `src/`, or the directory itself without one."""
    src = workspace / 'src'
    return src if src.is_dir() else workspace


# -- a workspace nearby that this shell does not use --------------------------------------------

_NEARBY_CHILDREN = 200  # directories below the current one looked at as workspace roots


@dataclass(frozen=True)
class Nearby:
    """A workspace near the current directory that holds a package this process missed."""

    workspace: Path
    built: bool  # its install/ has the package (colcon built it; not sourced here)
    sources: bool  # its src/ has the package

    def ways_in(self) -> str:
        """The two ways to use it, for a "not found" line."""
        ws = self.workspace
        source = f'source {ws}/install/setup.bash'
        variable = f'export {WORKSPACE_ENV}={ws}'
        if self.built:
            where = f'it is built in the workspace {ws}, which this shell has not sourced: '
            return where + (f'`{source}`, or `{variable}`' if self.sources else f'`{source}`')
        return (
            f'it is in the workspace {ws}, which this shell does not use: `colcon build` '
            f'there and `{source}`, or `{variable}`'
        )


def _installed(install: Path, package: str) -> bool:
    """Does a colcon install/ (isolated or merged) hold `package`?"""
    marker = Path('share') / 'ament_index' / 'resource_index' / 'packages' / package
    return (
        (install / package / marker).is_file()
        or (install / package / 'share' / package / MANIFEST).is_file()
        or (install / marker).is_file()
    )


def _sources_have(src: Path, package: str) -> bool:
    for directory in _package_dirs(src, _DETECT_DEPTH, _DETECT_DIRS):
        if directory.name == package:
            return True
        try:
            if read_manifest(directory / MANIFEST).name == package:
                return True
        except ManifestError:
            continue
    return False


def find_nearby(package: str, cwd: Path, in_use: list[Path] | None = None) -> Nearby | None:
    """A workspace around `cwd` (it and its parents) or just below it (its subdirectories)
    whose `src/` or unsourced `install/` holds `package`; workspaces in `in_use` are skipped
    (their packages were already seen). Looked for only when a lookup has failed."""
    skip = {ws.resolve() for ws in in_use or ()}
    roots: list[Path] = [cwd, *cwd.parents]
    try:
        children = sorted(
            (e for e in os.scandir(cwd) if not e.name.startswith('.') and _is_dir(e)),
            key=lambda e: e.name,
        )
        roots += [Path(e.path) for e in children[:_NEARBY_CHILDREN]]
    except OSError:
        pass
    for root in roots:
        try:
            key = root.resolve()
        except (OSError, RuntimeError):
            continue
        if key in skip or inside_ros2lite(root):
            continue
        skip.add(key)
        src, install = root / 'src', root / 'install'
        built = install.is_dir() and _installed(install, package)
        sources = src.is_dir() and _sources_have(src, package)
        if built or sources:
            return Nearby(root, built, sources)
    return None
