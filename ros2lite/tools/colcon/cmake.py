"""Reading an `ament_cmake` package's CMakeLists.txt without CMake: which interface files its
`rosidl_generate_interfaces` call names, which files its plain `install()` calls copy, and
which commands need a real CMake build.

Only what the ROS courses write is understood: commands with quoted and unquoted arguments,
comments, `set(VAR ...)`, `list(APPEND VAR ...)` and `${VAR}` (with `PROJECT_NAME` and
`CMAKE_CURRENT_SOURCE_DIR`).
Anything else is not guessed at: a command ros2lite cannot carry out is reported by name and
line, so the build can say what was skipped.
"""

from __future__ import annotations

import os
import re
from dataclasses import dataclass, field
from pathlib import Path

from ros2lite.exceptions import Ros2liteError

__all__ = [
    'CMakeCall',
    'CMakeError',
    'CMakePackage',
    'FileInstall',
    'file_install_plan',
    'mentions_rosidl',
    'parse_calls',
    'read_cmake_package',
]

CMAKE_LISTS = 'CMakeLists.txt'
_MAX_BYTES = 1 << 20

# commands that configure, find or declare, and so have nothing to build without CMake
_HARMLESS = frozenset(
    {
        'cmake_minimum_required',
        'project',
        'find_package',
        'set',
        'unset',
        'if',
        'elseif',
        'else',
        'endif',
        'option',
        'message',
        'add_compile_options',
        'include_directories',
        'ament_package',
        'ament_export_dependencies',
        'ament_lint_auto_find_test_dependencies',
        'ament_add_gtest',
        'ament_add_pytest_test',
        'rosidl_generate_interfaces',
        'rosidl_get_typesupport_target',
        'foreach',
        'endforeach',
    }
)
# rosidl_generate_interfaces' keywords: everything after one is not an interface file
_ROSIDL_KEYWORDS = frozenset(
    {
        'DEPENDENCIES',
        'LIBRARY_NAME',
        'SKIP_INSTALL',
        'SKIP_GROUP_MEMBERSHIP_CHECK',
        'ADD_LINTER_TESTS',
    }
)
_TOKEN = re.compile(
    r'''
    (?P<newline>\n)
  | (?P<space>[ \t\r]+)
  | (?P<bracket_comment>\#\[(?P<eq>=*)\[.*?\](?P=eq)\])
  | (?P<comment>\#[^\n]*)
  | (?P<quoted>"(?:[^"\\]|\\.)*")
  | (?P<open>\()
  | (?P<close>\))
  | (?P<word>[^\s()#"]+)
    ''',
    re.VERBOSE | re.DOTALL,
)
_NAME = re.compile(r'[A-Za-z_][A-Za-z0-9_]*\Z')
_REF = re.compile(r'\$\{([A-Za-z_][A-Za-z0-9_]*)\}')


class CMakeError(Ros2liteError, ValueError):
    """A CMakeLists.txt that cannot be read the way ros2lite reads one (file and line)."""


@dataclass(frozen=True)
class CMakeCall:
    """One command invocation: its name (lower case), arguments as written, first line."""

    name: str
    args: tuple[str, ...]
    line: int


@dataclass(frozen=True)
class FileInstall:
    """One `install(DIRECTORY|FILES|PROGRAMS <sources> DESTINATION <dest>)` call: sources
    relative to the package, the destination relative to the install prefix."""

    kind: str  # DIRECTORY | FILES | PROGRAMS
    sources: tuple[str, ...]
    destination: str
    line: int


@dataclass
class CMakePackage:
    """What a CMakeLists.txt asks for, as far as ros2lite can carry it out."""

    path: Path
    interfaces: list[str] = field(default_factory=list)  # relative to the package, in order
    dependencies: list[str] = field(default_factory=list)  # rosidl DEPENDENCIES
    rosidl_line: int = 0  # the rosidl_generate_interfaces call (0: none)
    unbuilt: list[CMakeCall] = field(default_factory=list)  # what needs a real CMake build
    installs: list[FileInstall] = field(default_factory=list)  # install(DIRECTORY|FILES|...)

    @property
    def has_interfaces(self) -> bool:
        """Does the package generate interfaces (so ros2lite can install it)?"""
        return self.rosidl_line > 0

    def unbuilt_summary(self, limit: int = 3) -> str:
        """`add_executable (line 12), install (line 20) and 2 more`, for a one-line report."""
        shown = [f'{c.name} (line {c.line})' for c in self.unbuilt[:limit]]
        more = len(self.unbuilt) - limit
        if more > 0:
            shown.append(f'{more} more')
        return ', '.join(shown)


def _unquote(token: str) -> str:
    body = token[1:-1]
    return re.sub(r'\\(.)', lambda m: {'n': '\n', 't': '\t'}.get(m[1], m[1]), body)


def parse_calls(text: str, source: str = CMAKE_LISTS) -> list[CMakeCall]:
    """Split CMake text into command calls; a stray character or an unclosed call is a
    CMakeError naming `source` and the line."""
    calls: list[CMakeCall] = []
    line = 1
    pos = 0
    name: str | None = None
    start = 0
    depth = 0
    args: list[str] = []
    while pos < len(text):
        m = _TOKEN.match(text, pos)
        if m is None:  # pragma: no cover - the word class takes every other character
            raise CMakeError(f'{source}:{line}: cannot read {text[pos]!r}')
        kind = m.lastgroup
        token = m[0]
        pos = m.end()
        if kind == 'eq':  # pragma: no cover - a sub-group, never the last one
            continue
        if kind in ('newline', 'space', 'comment', 'bracket_comment'):
            line += token.count('\n')
            continue
        if name is None:
            if kind != 'word' or not _NAME.match(token):
                raise CMakeError(f'{source}:{line}: expected a command, found {token!r}')
            name, start, args = token.lower(), line, []
            m2 = re.compile(r'[ \t]*\(').match(text, pos)
            if m2 is None:
                raise CMakeError(f"{source}:{line}: expected '(' after {token}")
            pos = m2.end()
            depth = 1
            continue
        if kind == 'open':
            depth += 1
            args.append(token)
        elif kind == 'close':
            depth -= 1
            if depth == 0:
                calls.append(CMakeCall(name, tuple(args), start))
                name = None
            else:
                args.append(token)
        elif kind == 'quoted':
            line += token.count('\n')
            args.append(token)
        else:
            args.append(token)
    if name is not None:
        raise CMakeError(f"{source}:{start}: {name}( is never closed with ')'")
    return calls


class _Variables:
    """`set()` values as the file goes, for `${VAR}` in the calls ros2lite reads."""

    def __init__(self, package_dir: Path, source: str) -> None:
        self.values: dict[str, list[str]] = {
            'CMAKE_CURRENT_SOURCE_DIR': [str(package_dir)],
            'CMAKE_SOURCE_DIR': [str(package_dir)],
            'PROJECT_SOURCE_DIR': [str(package_dir)],
        }
        self.source = source

    def expand(self, call: CMakeCall) -> list[str]:
        """The call's arguments with variables replaced (an unquoted list variable gives
        its items as arguments, as CMake does)."""
        out: list[str] = []
        for raw in call.args:
            if raw.startswith('"'):
                out.append(self._substitute(_unquote(raw), call.line))
                continue
            value = self._substitute(raw, call.line)
            out += [item for item in value.split(';') if item]
        return out

    def _substitute(self, text: str, line: int) -> str:
        def one(m: re.Match[str]) -> str:
            if m[1] not in self.values:
                raise CMakeError(
                    f'{self.source}:{line}: ${{{m[1]}}} is not set before this line '
                    '(ros2lite reads set() and project(), not other CMake)'
                )
            return ';'.join(self.values[m[1]])

        for _ in range(8):  # nested ${A_${B}} at most a few levels deep
            new = _REF.sub(one, text)
            if new == text:
                break
            text = new
        return text


def mentions_rosidl(package_dir: Path) -> bool:
    """Does the CMakeLists.txt name rosidl_generate_interfaces at all (for a file that
    cannot be read as a whole: is it meant to be an interface package)?"""
    try:
        text = (package_dir / CMAKE_LISTS).read_text(encoding='utf-8', errors='replace')
    except OSError:
        return False
    return re.search(r'^[ \t]*rosidl_generate_interfaces[ \t]*\(', text, re.M | re.I) is not None


def read_cmake_package(package_dir: Path, package_name: str) -> CMakePackage:
    """Read `package_dir`/CMakeLists.txt: interface files and rosidl DEPENDENCIES, and every
    call that needs a real CMake build. A missing or unreadable file is a CMakeError."""
    path = package_dir / CMAKE_LISTS
    try:
        if path.stat().st_size > _MAX_BYTES:
            raise CMakeError(f'{path}: larger than {_MAX_BYTES} bytes; not a CMakeLists.txt')
        text = path.read_text(encoding='utf-8')
    except (OSError, UnicodeDecodeError) as e:
        raise CMakeError(f'{path}: cannot be read: {e}') from None
    source = str(path)
    variables = _Variables(package_dir, source)
    found = CMakePackage(path)
    for call in parse_calls(text, source):
        if call.name == 'project':
            values = variables.expand(call)
            if values:
                variables.values['PROJECT_NAME'] = [values[0]]
        elif call.name == 'set' and call.args:
            var = call.args[0].strip('"')
            try:
                values = variables.expand(call)[1:]
            except CMakeError:  # set from something ros2lite does not know: unknown too
                variables.values.pop(var, None)
                continue
            variables.values[var] = [v for v in values if v not in ('CACHE', 'PARENT_SCOPE')]
        elif call.name == 'list' and call.args and call.args[0] == 'APPEND':
            try:
                values = variables.expand(call)
            except CMakeError:
                found.unbuilt.append(call)
                continue
            if len(values) > 1:
                variables.values.setdefault(values[1], []).extend(values[2:])
        elif call.name == 'install' and call.args and call.args[0] in _INSTALL_KINDS:
            try:
                found.installs.append(_read_install(call, variables.expand(call), package_dir))
            except CMakeError:
                found.unbuilt.append(call)  # more than ros2lite copies: CMake's business
        elif call.name == 'rosidl_generate_interfaces':
            _read_rosidl(call, variables.expand(call), package_dir, package_name, found, source)
        elif call.name not in _HARMLESS:
            found.unbuilt.append(call)
    return found


_INSTALL_KINDS = ('DIRECTORY', 'FILES', 'PROGRAMS')


def _read_install(call: CMakeCall, values: list[str], package_dir: Path) -> FileInstall:
    """An install() ros2lite can carry out: sources inside the package, one relative
    DESTINATION, no other option (PATTERN, TARGETS, ... stay CMake's)."""
    kind, rest = values[0], values[1:]
    if 'DESTINATION' not in rest:
        raise CMakeError(f'line {call.line}: install({kind}) without DESTINATION')
    at = rest.index('DESTINATION')
    sources, tail = rest[:at], rest[at + 1 :]
    if len(tail) != 1 or not sources or Path(tail[0]).is_absolute() or '..' in Path(tail[0]).parts:
        raise CMakeError(f'line {call.line}: install({kind}) beyond what ros2lite copies')
    relative = tuple(
        _relative(src, package_dir, str(package_dir / CMAKE_LISTS), call.line)
        + ('/' if src.endswith('/') else '')
        for src in sources
    )
    return FileInstall(kind, relative, Path(tail[0]).as_posix(), call.line)


def _read_rosidl(
    call: CMakeCall,
    values: list[str],
    package_dir: Path,
    package_name: str,
    found: CMakePackage,
    source: str,
) -> None:
    if found.rosidl_line:
        raise CMakeError(
            f'{source}:{call.line}: a second rosidl_generate_interfaces call '
            f'(the first is on line {found.rosidl_line}); ros2lite reads one per package'
        )
    if not values:
        raise CMakeError(f'{source}:{call.line}: rosidl_generate_interfaces() names no target')
    found.rosidl_line = call.line
    keyword = ''
    for value in values[1:]:
        if value in _ROSIDL_KEYWORDS:
            keyword = value
            continue
        if keyword == 'DEPENDENCIES':
            found.dependencies.append(value)
        elif not keyword:
            found.interfaces.append(_relative(value, package_dir, source, call.line))
    if not found.interfaces:
        raise CMakeError(
            f'{source}:{call.line}: rosidl_generate_interfaces({package_name} ...) lists '
            'no interface files'
        )


def _relative(value: str, package_dir: Path, source: str, line: int) -> str:
    """An interface file named in the call, relative to the package (`msg/Age.msg`)."""
    # rosidl also accepts `<base dir>:<relative path>`
    base, sep, rest = value.rpartition(':')
    if sep and base and not re.fullmatch(r'[A-Za-z]', base):
        value = str(Path(base) / rest)
    path = Path(value)
    if path.is_absolute():
        try:
            path = path.resolve().relative_to(package_dir.resolve())
        except ValueError:
            raise CMakeError(
                f'{source}:{line}: {value} is outside the package; ros2lite installs only '
                "the package's own interface files"
            ) from None
    if '..' in path.parts:
        raise CMakeError(f'{source}:{line}: {value} leaves the package directory')
    return path.as_posix()


def file_install_plan(
    package_dir: Path, installs: list[FileInstall]
) -> list[tuple[str, str, bool]]:
    """(source relative to the package, destination relative to the prefix, executable) for
    every file the install() calls copy, as CMake lays them out: `DIRECTORY launch` puts the
    folder itself under the destination, `DIRECTORY launch/` its contents. A source that does
    not exist is a CMakeError naming the call's line."""
    plan: list[tuple[str, str, bool]] = []
    for item in installs:
        for source in item.sources:
            full = package_dir / source
            if item.kind != 'DIRECTORY':
                if not full.is_file():
                    raise CMakeError(
                        f'{package_dir / CMAKE_LISTS}:{item.line}: install({item.kind}) '
                        f'names {source}, which is not a file'
                    )
                plan.append((source, f'{item.destination}/{full.name}', item.kind == 'PROGRAMS'))
                continue
            if not full.is_dir() or full.is_symlink():
                raise CMakeError(
                    f'{package_dir / CMAKE_LISTS}:{item.line}: install(DIRECTORY) names '
                    f'{source}, which is not a folder'
                )
            top = Path(item.destination)
            if not source.endswith('/'):
                top = top / full.name
            for dirpath, dirnames, filenames in os.walk(full):
                dirnames.sort()
                rel = Path(dirpath).relative_to(full)
                for name in sorted(filenames):
                    if (Path(dirpath) / name).is_file():
                        src = (Path(source.rstrip('/')) / rel / name).as_posix()
                        plan.append((src, (top / rel / name).as_posix(), False))
    return plan
