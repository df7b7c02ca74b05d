"""Launch description sources: where an included launch description comes from.

A Python launch file is a module defining ``generate_launch_description()``; it is imported
with the compat directory on ``sys.path``, so its ``import launch`` / ``launch_ros`` /
``ament_index_python`` find ros2lite's faces of those packages. XML and YAML files go
through :mod:`.frontend`. :func:`load_launch_file` picks by extension.

The plain :class:`LaunchDescriptionSource` (a description given directly) stands in
:mod:`.actions`, beside the include that wraps a description in one. The XML and YAML reader
is handed in by :mod:`ros2lite.launch` (:func:`use_frontend`): the frontends' ``<include>``
makes the sources of this module, so this module does not import the frontends.
"""

from __future__ import annotations

import importlib.util
import itertools
import sys
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING

from ros2lite.util.files import read_bounded

from .actions import LaunchDescription, LaunchDescriptionSource, including
from .errors import InvalidFrontendLaunchFileError, LaunchError
from .substitutions import (
    SomeSubstitutionsType,
    TextSubstitution,
    describe_substitutions,
    normalize_to_list_of_substitutions,
    perform_substitutions,
)

if TYPE_CHECKING:
    from .context import LaunchContext

__all__ = [
    'AnyLaunchDescriptionSource',
    'FrontendLaunchDescriptionSource',
    'LaunchDescriptionSource',
    'PythonLaunchDescriptionSource',
    'XMLLaunchDescriptionSource',
    'YAMLLaunchDescriptionSource',
    'load_launch_file',
    'load_python_launch_file',
    'use_frontend',
]

_modules = itertools.count()

FRONTEND_EXTENSIONS = {'.xml': 'xml', '.yaml': 'yaml', '.yml': 'yaml'}
"""The extensions of XML and YAML launch files, and the frontend kind of each."""

FrontendReader = Callable[[Path, str], LaunchDescription]
"""Reads an XML or YAML launch file: `reader(path, 'xml' | 'yaml')`."""

_frontend: FrontendReader | None = None


def use_frontend(reader: FrontendReader) -> None:
    """Read XML and YAML launch files with `reader` (ros2lite.launch hands in
    :mod:`.frontend`'s when it is imported)."""
    global _frontend
    _frontend = reader


def _read_frontend(path: Path, kind: str) -> LaunchDescription:
    if _frontend is None:  # ros2lite.launch sets it, and importing this module runs that first
        raise LaunchError(f"'{path}': no reader for {kind} launch files (import ros2lite.launch)")
    return _frontend(path, kind)


def _compat_on_path() -> None:
    from ros2lite.pkg.environment import COMPAT_DIR

    if str(COMPAT_DIR) not in sys.path:
        sys.path.insert(0, str(COMPAT_DIR))


# the largest Python launch file read (upstream's biggest are a few KB)
_PYTHON_LIMIT = 16 * 1024 * 1024


def load_python_launch_file(path: Path) -> LaunchDescription:
    """Run a Python launch file and return what its ``generate_launch_description()`` gives."""
    _compat_on_path()
    if not path.exists():
        raise LaunchError(f"launch file '{path}' does not exist")
    # read bounded and only if a regular file (a link to /dev/zero, a FIFO), then compiled
    source = read_bounded(path, _PYTHON_LIMIT, LaunchError, 'a Python launch file')
    name = f'_ros2lite_launch_file_{next(_modules)}'
    spec = importlib.util.spec_from_file_location(name, path)
    if spec is None or spec.loader is None:
        raise LaunchError(f"launch file '{path}' cannot be loaded as Python")
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module
    try:
        code = compile(source, str(path), 'exec')
        exec(code, module.__dict__)  # what the spec's loader would run, from the bytes read
    except SyntaxError as e:
        raise LaunchError(f"launch file '{path}' is not valid Python: {e}") from None
    generate = getattr(module, 'generate_launch_description', None)
    if not callable(generate):
        raise LaunchError(
            f"launch file at '{path}' does not contain the required function "
            "'generate_launch_description()'"
        )
    description = generate()
    if not isinstance(description, LaunchDescription):
        raise LaunchError(
            f"generate_launch_description() of '{path}' returned "
            f'{type(description).__name__}, not a LaunchDescription'
        )
    description.source_path = str(path.resolve())
    return description


def load_launch_file(path: Path, kind: str | None = None) -> LaunchDescription:
    """Any launch file: 'python', 'xml' or 'yaml' (by extension when `kind` is None; a file
    with another extension is tried as each in turn). A file already on the way to itself
    is refused (see `including`)."""
    with including(str(path.resolve())):
        return _load(path, kind)


def _load(path: Path, kind: str | None) -> LaunchDescription:
    if kind is None:
        suffix = path.suffix.lower()
        kind = 'python' if suffix == '.py' else FRONTEND_EXTENSIONS.get(suffix)
    if kind == 'python':
        return load_python_launch_file(path)
    if kind in ('xml', 'yaml'):
        return _read_frontend(path, kind)
    errors = []
    for attempt in ('xml', 'yaml'):
        try:
            return _read_frontend(path, attempt)
        except InvalidFrontendLaunchFileError as e:
            errors.append(str(e))
    try:
        return load_python_launch_file(path)
    except Exception as e:  # not Python either: say what each reader found
        errors.append(str(e))
    raise LaunchError(f"'{path}' is not a launch file ({'; '.join(errors)})")


class _FileSource(LaunchDescriptionSource):
    kind: str | None = None

    def __init__(self, launch_file_path: SomeSubstitutionsType | Path) -> None:
        super().__init__(None, '<unknown>')
        self.path = normalize_to_list_of_substitutions(
            str(launch_file_path) if isinstance(launch_file_path, Path) else launch_file_path
        )

    def try_get_launch_description_without_context(self) -> LaunchDescription | None:

        if self._description is None and all(isinstance(s, TextSubstitution) for s in self.path):
            path = Path(''.join(s.text for s in self.path))  # type: ignore[attr-defined]
            self.location = str(path)
            self._description = load_launch_file(path, self.kind)
        return self._description

    def get_launch_description(self, context: LaunchContext) -> LaunchDescription:
        if self._description is None:
            path = Path(perform_substitutions(context, self.path))
            self.location = str(path)
            self._description = load_launch_file(path, self.kind)
        return self._description

    def describe(self) -> str:
        return f'{self.method} at {describe_substitutions(self.path)}'


class PythonLaunchDescriptionSource(_FileSource):
    """A Python launch file."""

    kind = 'python'
    method = 'interpreted python launch file'


class FrontendLaunchDescriptionSource(_FileSource):
    """An XML or YAML launch file (by extension)."""

    method = 'interpreted frontend launch file'


class XMLLaunchDescriptionSource(FrontendLaunchDescriptionSource):
    """An XML launch file, whatever its extension."""

    kind = 'xml'


class YAMLLaunchDescriptionSource(FrontendLaunchDescriptionSource):
    """A YAML launch file, whatever its extension."""

    kind = 'yaml'


class AnyLaunchDescriptionSource(_FileSource):
    """A launch file of any kind, by extension."""

    method = 'interpreted launch file'
