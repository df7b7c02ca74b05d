"""An interface package built without CMake: its `.msg/.srv/.action` files checked with
ros2lite's parser, and the files a ROS install of it holds, listed for the installer.

ros2lite needs no generated code: it reads the definitions themselves wherever an ament
prefix holds them (`share/<pkg>/msg/Age.msg`). So "building" an interface package is checking
what rosidl would refuse — syntax, names, types nobody provides, dependencies the call does
not declare — each as one line naming the file and line, then installing the files with the
package's manifest and its ament index entries, as ROS does.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from dataclasses import dataclass
from pathlib import Path

from ros2lite.exceptions import Ros2liteError
from ros2lite.interfaces.errors import InterfaceError
from ros2lite.interfaces.parser import (
    Field,
    MessageDef,
    parse_action,
    parse_line,
    parse_message,
    parse_service,
    split_comment,
    validate_type_name,
)

from .cmake import CMakePackage

__all__ = [
    'InterfaceFile',
    'InterfacePackageError',
    'check_interfaces',
    'install_plan',
    'resource_index_entry',
]

_KIND_OF = {'.msg': 'msg', '.srv': 'srv', '.action': 'action'}
_SEPARATOR = '---'
_MAX_BYTES = 1 << 20


class InterfacePackageError(Ros2liteError, ValueError):
    """An interface file rosidl would refuse; the message names the file and the line."""


@dataclass(frozen=True)
class InterfaceFile:
    """One checked interface file of the package."""

    relative: str  # 'msg/Age.msg'
    kind: str  # msg | srv | action
    name: str  # 'custom_interfaces/msg/Age'


def _read(path: Path, cmake: CMakePackage, relative: str) -> str:
    where = f'{cmake.path}:{cmake.rosidl_line}'
    if path.is_symlink() and not path.exists():
        raise InterfacePackageError(f'{where}: {relative} is a broken symbolic link')
    if not path.is_file():
        raise InterfacePackageError(f'{where}: {relative} does not exist')
    try:
        if path.stat().st_size > _MAX_BYTES:
            raise InterfacePackageError(f'{path}: larger than {_MAX_BYTES} bytes')
        return path.read_text(encoding='utf-8')
    except (OSError, UnicodeDecodeError) as e:
        raise InterfacePackageError(f'{path}: cannot be read: {e}') from None


def _parts(text: str, file: InterfaceFile, source: str) -> list[MessageDef]:
    """Parse the whole file (the parser's own errors carry file and line)."""
    try:
        if file.kind == 'msg':
            return [parse_message(text, file.name, source)]
        if file.kind == 'srv':
            srv = parse_service(text, file.name, source)
            return [srv.request, srv.response]
        act = parse_action(text, file.name, source)
        return [act.goal, act.result, act.feedback]
    except InterfaceError as e:
        raise InterfacePackageError(str(e)) from None


def _fields_by_line(text: str, package: str) -> Iterable[tuple[int, Field]]:
    """Each field with its line (the file already parsed, so every line parses)."""
    for lineno, raw in enumerate(text.splitlines(), start=1):
        code = split_comment(raw)[0].strip()
        if not code or code == _SEPARATOR:
            continue
        item = parse_line(code, package)
        if isinstance(item, Field):
            yield lineno, item


def check_interfaces(
    package_dir: Path,
    package: str,
    cmake: CMakePackage,
    provides: Callable[[str], bool],
) -> list[InterfaceFile]:
    """Check every file `cmake` names; `provides('pkg/msg/Name')` says whether another package
    (a dependency or an installed package) defines a message. Returns the files in order; the
    first problem is an InterfacePackageError."""
    files: list[InterfaceFile] = []
    where = f'{cmake.path}:{cmake.rosidl_line}'
    for relative in cmake.interfaces:
        path = Path(relative)
        kind = _KIND_OF.get(path.suffix)
        if kind is None:
            raise InterfacePackageError(
                f'{where}: {relative}: ros2lite reads .msg, .srv and .action files'
                + (
                    ', not .idl (write the interface as a .msg/.srv/.action file)'
                    if path.suffix == '.idl'
                    else ''
                )
            )
        if path.parent.as_posix() != kind:
            raise InterfacePackageError(
                f'{where}: {relative}: a {path.suffix} file belongs in the package\'s '
                f'{kind}/ folder ({kind}/{path.name})'
            )
        try:
            validate_type_name(f'{package}/{kind}/{path.stem}')
        except InterfaceError as e:
            raise InterfacePackageError(f'{package_dir / relative}: {e}') from None
        files.append(InterfaceFile(relative, kind, f'{package}/{kind}/{path.stem}'))

    names = [f.name for f in files]
    if len(set(names)) != len(names):
        twice = sorted({n for n in names if names.count(n) > 1})
        raise InterfacePackageError(f'{where}: {twice[0]} is listed twice')
    own_messages = {f.name for f in files if f.kind == 'msg'}
    for file in files:
        source = str(package_dir / file.relative)
        text = _read(package_dir / file.relative, cmake, file.relative)
        _parts(text, file, source)
        for lineno, fld in _fields_by_line(text, package):
            base = fld.type.base
            if fld.type.is_primitive:
                continue
            owner = base.split('/')[0]
            if owner == package:
                if base not in own_messages:
                    raise InterfacePackageError(
                        f'{source}:{lineno}: {base} is not among the files '
                        f'rosidl_generate_interfaces lists ({where})'
                    )
                continue
            if owner not in cmake.dependencies:
                raise InterfacePackageError(
                    f"{source}:{lineno}: {base} comes from package '{owner}', which "
                    f'rosidl_generate_interfaces does not list in DEPENDENCIES ({where})'
                )
            if not provides(base):
                raise InterfacePackageError(
                    f"{source}:{lineno}: no package provides {base} (is '{owner}' "
                    'built, installed or sourced?)'
                )
    return files


def install_plan(package: str, files: Iterable[InterfaceFile]) -> list[tuple[str, str]]:
    """(source relative to the package, destination relative to the install prefix) for
    each interface file and the manifest, as an ament_cmake build installs them."""
    plan = [(f.relative, f'share/{package}/{f.relative}') for f in files]
    plan.append(('package.xml', f'share/{package}/package.xml'))
    return plan


def resource_index_entry(files: Iterable[InterfaceFile]) -> str:
    """The `rosidl_interfaces` resource's content: one `msg/Age.msg` line per interface
    (ROS lists its generated `.idl` files too; ros2lite generates none)."""
    return ''.join(f'{f.relative}\n' for f in files)
