"""What an ament_python package's `setup.py`/`setup.cfg` declare, read without running them.

`setup.py` is a program, and a workspace may hold someone else's: it is parsed with :mod:`ast`
and only literal values are evaluated — strings, numbers, lists, tuples, dicts, names bound
to such values at module level, `+` of strings or lists, f-strings of those, and
`os.path.join`. That covers what `ros2 pkg create` writes and what the tutorials add
(`package_name = 'py_pubsub'`, `'talker = py_pubsub.publisher_member_function:main'`).
Anything else is left unknown, never executed. `setup.cfg` is read as INI without
interpolation (its values contain `$base`).

What would stop colcon building the package is kept as a :class:`PackageFileError` naming the
file and line: a setup.py that is not Python or calls no `setup()`, an entry point that does
not parse, a setup.cfg that is not INI, an ament_python package with neither file.
"""

from __future__ import annotations

import ast
import configparser
import os
import re
from collections.abc import Iterable
from dataclasses import dataclass, field
from pathlib import Path

from ros2lite.util.files import ReadRefused, read_bounded

from .errors import PackageFileError

__all__ = ['PythonPackageInfo', 'parse_console_script', 'read_python_package']

_MAX_BYTES = 1 << 20

# `name = package.module:function [extra]`, as setuptools writes console_scripts
_SCRIPT = re.compile(
    r'\s*(?P<name>[A-Za-z0-9_.+-]+)\s*=\s*'
    r'(?P<module>[A-Za-z_][\w]*(?:\.[A-Za-z_][\w]*)*)'
    r'(?:\s*:\s*(?P<attr>[A-Za-z_][\w]*(?:\.[A-Za-z_][\w]*)*))?'
    r'\s*(?:\[[^\]]*\])?\s*\Z'
)


class _Unknown:
    """A value the reader could not (or would not) evaluate."""


UNKNOWN = _Unknown()


@dataclass
class PythonPackageInfo:
    """Console scripts (`name` → `module:attr`), where the package's modules live, and what
    in its files colcon would refuse."""

    console_scripts: dict[str, str] = field(default_factory=dict)
    package_root: Path | None = None
    problems: list[PackageFileError] = field(default_factory=list)


def parse_console_script(entry: str) -> tuple[str, str] | None:
    """('talker', 'py_pubsub.publisher_member_function:main') from one console_scripts line,
    or None when the line is not a well-formed entry point."""
    m = _SCRIPT.match(entry)
    if m is None:
        return None
    target = m['module'] + (':' + m['attr'] if m['attr'] else '')
    return m['name'], target


# -- setup.py -----------------------------------------------------------------------------------


class _Evaluator:
    """Evaluates literal-ish expressions against module-level names; UNKNOWN otherwise."""

    def __init__(self) -> None:
        self.names: dict[str, object] = {}

    def value(self, node: ast.AST) -> object:
        if isinstance(node, ast.Constant) and isinstance(
            node.value, (str, int, float, bool, type(None))
        ):
            return node.value
        if isinstance(node, (ast.List, ast.Tuple, ast.Set)):
            items = [self.value(e) for e in node.elts]
            return UNKNOWN if any(i is UNKNOWN for i in items) else items
        if isinstance(node, ast.Dict):
            result: dict[str | int, object] = {}
            for k, v in zip(node.keys, node.values, strict=True):
                key = self.value(k) if k is not None else UNKNOWN
                if isinstance(key, (str, int)):
                    result[key] = self.value(v)
            return result
        if isinstance(node, ast.Name):
            return self.names.get(node.id, UNKNOWN)
        if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Add):
            left, right = self.value(node.left), self.value(node.right)
            if isinstance(left, str) and isinstance(right, str):
                return left + right
            if isinstance(left, list) and isinstance(right, list):
                return left + right
            return UNKNOWN
        if isinstance(node, ast.JoinedStr):
            parts = []
            for piece in node.values:
                if isinstance(piece, ast.Constant) and isinstance(piece.value, str):
                    parts.append(piece.value)
                elif (
                    isinstance(piece, ast.FormattedValue)
                    and piece.format_spec is None
                    and piece.conversion in (-1, ord('s'))
                ):
                    inner = self.value(piece.value)
                    if not isinstance(inner, (str, int, float)):
                        return UNKNOWN
                    parts.append(str(inner))
                else:
                    return UNKNOWN
            return ''.join(parts)
        if isinstance(node, ast.Call) and _dotted(node.func) in ('os.path.join', 'path.join'):
            args = [self.value(a) for a in node.args]
            texts = [a for a in args if isinstance(a, str)]
            if node.keywords or not args or len(texts) != len(args):
                return UNKNOWN
            return os.path.join(*texts)
        return UNKNOWN


def _dotted(node: ast.AST) -> str:
    if isinstance(node, ast.Name):
        return node.id
    if isinstance(node, ast.Attribute):
        return f'{_dotted(node.value)}.{node.attr}'
    return ''


def _setup_call(tree: ast.Module) -> ast.Call | None:
    for node in ast.walk(tree):
        if isinstance(node, ast.Call) and _dotted(node.func) in ('setup', 'setuptools.setup'):
            return node
    return None


def _setup_keywords(tree: ast.Module, call: ast.Call) -> dict[str, object]:
    """The keyword arguments of the `setup(...)` call, evaluated where literal."""
    ev = _Evaluator()
    for stmt in tree.body:
        if (
            isinstance(stmt, ast.Assign)
            and len(stmt.targets) == 1
            and isinstance(stmt.targets[0], ast.Name)
        ):
            ev.names[stmt.targets[0].id] = ev.value(stmt.value)
        elif isinstance(stmt, ast.AnnAssign) and isinstance(stmt.target, ast.Name) and stmt.value:
            ev.names[stmt.target.id] = ev.value(stmt.value)
    return {kw.arg: ev.value(kw.value) for kw in call.keywords if kw.arg is not None}


def _string_lines(tree: ast.AST) -> dict[str, int]:
    """Each string constant in `tree` → the line it starts on (first one wins)."""
    lines: dict[str, int] = {}
    for node in ast.walk(tree):
        if isinstance(node, ast.Constant) and isinstance(node.value, str):
            lines.setdefault(node.value, node.lineno)
    return lines


_SCRIPT_FORM = "expected 'name = package.module:function'"


def _scripts_from(value: object) -> Iterable[str]:
    """console_scripts lines from setup()'s entry_points (a dict, or an INI string)."""
    if isinstance(value, dict):
        scripts = value.get('console_scripts')
        if isinstance(scripts, str):
            return scripts.splitlines()
        if isinstance(scripts, list):
            return [s for s in scripts if isinstance(s, str)]
        return []
    if isinstance(value, str):
        parser = configparser.RawConfigParser()
        parser.optionxform = str  # type: ignore[assignment,method-assign]  # keep name case
        try:
            parser.read_string(value)
        except configparser.Error:
            return []
        if not parser.has_section('console_scripts'):
            return []
        return [f'{k} = {v}' for k, v in parser.items('console_scripts')]
    return []


def _read_text(path: Path) -> str | None:
    """The file's text, None when it cannot be read: too big, or no regular file (a size
    checked by stat() alone let a link to /dev/zero be read without end)."""
    try:
        return read_bounded(path, _MAX_BYTES, ReadRefused, 'a setup file').decode(
            'utf-8', 'replace'
        )
    except ReadRefused:
        return None


def _from_setup_py(path: Path, info: PythonPackageInfo) -> None:
    source = _read_text(path)
    if source is None:
        if path.exists():
            info.problems.append(PackageFileError(path, None, 'cannot be read'))
        return
    try:
        tree = ast.parse(source, filename=str(path))
    except SyntaxError as e:
        info.problems.append(PackageFileError(path, e.lineno, f'not valid Python: {e.msg}'))
        return
    except ValueError as e:  # a NUL byte
        info.problems.append(PackageFileError(path, None, f'not valid Python: {e}'))
        return
    call = _setup_call(tree)
    if call is None:
        info.problems.append(
            PackageFileError(path, 1, 'no setup() call: colcon cannot build the package')
        )
        return
    kwargs = _setup_keywords(tree, call)
    entry_points = next((kw.value for kw in call.keywords if kw.arg == 'entry_points'), None)
    lines = _string_lines(entry_points) if entry_points is not None else {}
    for line in _scripts_from(kwargs.get('entry_points')):
        parsed = parse_console_script(line)
        if parsed is not None:
            info.console_scripts.setdefault(*parsed)
        elif line.strip():
            where = lines.get(line, entry_points.lineno if entry_points is not None else None)
            info.problems.append(
                PackageFileError(path, where, f"entry point '{line.strip()}': {_SCRIPT_FORM}")
            )
    package_dir = kwargs.get('package_dir')
    if isinstance(package_dir, dict) and isinstance(package_dir.get(''), str):
        info.package_root = _inside(path.parent, package_dir[''])


# -- setup.cfg ----------------------------------------------------------------------------------


def _from_setup_cfg(path: Path, info: PythonPackageInfo) -> None:
    text = _read_text(path)
    if text is None:
        return
    parser = configparser.RawConfigParser()
    try:
        parser.read_string(text, source=str(path))
    except configparser.Error as e:
        info.problems.append(PackageFileError(path, _ini_line(e), f'not valid INI: {_ini_why(e)}'))
        return
    scripts = parser.get('options.entry_points', 'console_scripts', fallback='')
    for line in scripts.splitlines():
        parsed = parse_console_script(line)
        if parsed is not None:
            info.console_scripts.setdefault(*parsed)
        elif line.strip():
            where = _text_line(text, line.strip())
            info.problems.append(
                PackageFileError(path, where, f"entry point '{line.strip()}': {_SCRIPT_FORM}")
            )
    package_dir = parser.get('options', 'package_dir', fallback='')
    for line in package_dir.splitlines():
        key, eq, value = line.partition('=')
        if eq and not key.strip() and info.package_root is None:
            info.package_root = _inside(path.parent, value.strip())


def _ini_line(e: configparser.Error) -> int | None:
    line = getattr(e, 'lineno', None)
    if isinstance(line, int):
        return line
    errors = getattr(e, 'errors', None)  # a ParsingError's (line, text) pairs
    return int(errors[0][0]) if errors else None


def _ini_why(e: configparser.Error) -> str:
    if isinstance(e, configparser.MissingSectionHeaderError):
        return 'a line before the first [section]'
    if isinstance(e, configparser.ParsingError):
        errors = getattr(e, 'errors', None)
        return f'cannot parse {errors[0][1]}' if errors else 'cannot parse'
    if isinstance(e, (configparser.DuplicateSectionError, configparser.DuplicateOptionError)):
        return e.message.split(' (from ', 1)[0].split(': ', 1)[-1]
    return e.message


def _text_line(text: str, needle: str) -> int | None:
    for number, line in enumerate(text.splitlines(), start=1):
        if needle in line:
            return number
    return None


def _inside(base: Path, relative: str) -> Path | None:
    """`base/relative` if it stays inside `base`, else None (a hostile `../..`)."""
    candidate = (base / relative).resolve()
    try:
        candidate.relative_to(base.resolve())
    except ValueError:
        return None
    return candidate


def read_python_package(directory: Path) -> PythonPackageInfo:
    """Console scripts and module root of the ament_python package in `directory`;
    setup.py's entries win over setup.cfg's for the same name."""
    info = PythonPackageInfo()
    _from_setup_py(directory / 'setup.py', info)
    _from_setup_cfg(directory / 'setup.cfg', info)
    if not (directory / 'setup.py').exists() and not (directory / 'setup.cfg').exists():
        info.problems.append(
            PackageFileError(
                directory / 'setup.py', None, 'missing: an ament_python package needs one'
            )
        )
    if info.package_root is None:
        info.package_root = directory
    return info
