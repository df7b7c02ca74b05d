"""What `ros2lite launch` does, as functions: find a package's launch file, read
`name:=value` arguments, run a file (ros2launch's behaviour)."""

from __future__ import annotations

import os
from collections.abc import Sequence
from pathlib import Path
from typing import IO, TYPE_CHECKING

from ros2lite.pkg.workspace import SKIPPED_DIRS

from .actions import LaunchDescription, LaunchDescriptionEntity, SetLaunchConfiguration
from .errors import LaunchError
from .flow import IncludeLaunchDescription
from .service import LaunchService
from .sources import AnyLaunchDescriptionSource

if TYPE_CHECKING:
    from ros2lite.pkg.index import PackageIndex

    from .output import Style

__all__ = [
    'find_launch_file',
    'launch_a_launch_file',
    'launch_files',
    'parse_launch_arguments',
]


def parse_launch_arguments(arguments: Sequence[str]) -> list[tuple[str, str]]:
    """`name:=value` words → (name, value) pairs."""
    pairs = []
    for arg in arguments:
        name, sep, value = arg.partition(':=')
        if not sep or not name:
            raise LaunchError(
                f"malformed launch argument '{arg}', expected format '<name>:=<value>'"
            )
        pairs.append((name, value))
    return pairs


def find_launch_file(
    package: str, file_name: str, index: PackageIndex | None = None
) -> tuple[Path, str | None]:
    """The launch file `file_name` anywhere under the package's share directory (a
    workspace package's source directory); and a note when a stand-in package was used
    (e.g. demo_nodes_py for an uninstalled demo_nodes_cpp)."""
    from ros2lite.pkg.executables import equivalent
    from ros2lite.pkg.index import PackageIndex

    idx = index if index is not None else PackageIndex()
    pkg = idx.find(package)
    note = None
    if pkg is None:
        twin = equivalent(package, idx)
        if twin is not None and twin.share is not None and _matches(twin.share, file_name):
            pkg = twin
            note = (
                f'{package} (C++) is not installed; launching {twin.name} {file_name}, '
                'its Python equivalent'
            )
        elif twin is not None:
            raise LaunchError(
                f"{package} (C++) is not installed, and {twin.name}, its Python equivalent, "
                f"has no launch file '{file_name}'"
            )
    if pkg is None:
        raise idx.not_found(package)
    if pkg.share is None:
        raise LaunchError(f"package '{package}' has no share directory to hold launch files")
    found = _matches(pkg.share, file_name)
    if not found:
        raise LaunchError(
            f"file '{file_name}' was not found in the share directory of package "
            f"'{package}' which is at '{pkg.share}'"
        )
    if len(found) > 1:
        raise LaunchError(
            f"file '{file_name}' was found more than once in the share directory of package "
            f"'{package}': {[str(p) for p in found]}"
        )
    return found[0], note


def _is_launch_file(name: str) -> bool:
    """Names launch files go by: `x.launch.py|xml|yaml|yml`, and `x_launch.py` (older)."""
    stem, dot, ext = name.rpartition('.')
    return (
        bool(dot) and ext in ('py', 'xml', 'yaml', 'yml') and stem.endswith(('.launch', '_launch'))
    )


def launch_files(package: str, index: PackageIndex | None = None) -> list[str]:
    """The launch file names in a package's share directory (for completion), sorted."""
    from ros2lite.pkg.index import PackageIndex

    pkg = (index if index is not None else PackageIndex()).find(package)
    if pkg is None or pkg.share is None:
        return []
    names: set[str] = set()
    for _dirpath, dirnames, filenames in os.walk(pkg.share):
        dirnames[:] = [d for d in dirnames if not d.startswith('.') and d not in SKIPPED_DIRS]
        names.update(f for f in filenames if _is_launch_file(f))
    return sorted(names)


def _matches(share: Path, file_name: str) -> list[Path]:
    found = []
    for dirpath, dirnames, filenames in os.walk(share):
        dirnames[:] = sorted(d for d in dirnames if not d.startswith('.') and d not in SKIPPED_DIRS)
        if file_name in filenames:
            found.append(Path(dirpath) / file_name)
    return found


def launch_a_launch_file(
    path: Path,
    arguments: Sequence[tuple[str, str]],
    *,
    noninteractive: bool = False,
    debug: bool = False,
    launch_prefix: str | None = None,
    launch_prefix_filter: str | None = None,
    output_override: str | None = None,
    style: Style | None = None,
    stream: IO[str] | None = None,
    notes: Sequence[str] = (),
    index: PackageIndex | None = None,
) -> int:
    """Run the launch file with its arguments until it is done or stopped; returns the
    launch's status (0, or 1 when the launch itself failed)."""
    service = LaunchService(
        argv=[f'{k}:={v}' for k, v in arguments],
        noninteractive=noninteractive,
        debug=debug,
        style=style,
        stream=stream,
        output_override=output_override,
        index=index,
    )
    for note in notes:
        service.pending_notes.append(note)
    entities: list[LaunchDescriptionEntity] = []
    if launch_prefix:
        entities.append(SetLaunchConfiguration('launch-prefix', launch_prefix))
    if launch_prefix_filter:
        entities.append(SetLaunchConfiguration('launch-prefix-filter', launch_prefix_filter))
    entities.append(
        IncludeLaunchDescription(
            AnyLaunchDescriptionSource(str(path)), launch_arguments=list(arguments)
        )
    )
    service.include_launch_description(LaunchDescription(entities))
    return service.run()
