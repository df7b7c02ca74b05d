"""Text forms of definitions: the rosbag2 `ros2msg` schema and `interface show` lines.

The schema text follows rosbag2's local definition source: the type's file verbatim, then every
dependency once (depth first, siblings sorted) after an 80-'=' line and `MSG: <name as written>`.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from .errors import InterfaceError, UnknownInterfaceError
from .parser import PRIMITIVES, SERVICE_SEPARATOR, Constant, MessageDef, parse_line, split_comment
from .registry import Registry, normalize_name

SEPARATOR = '=' * 80 + '\n'
_FIELD_TYPE_RE = re.compile(r'(?:^|\n)\s*([a-zA-Z0-9_/]+)(?:\[[^\]]*\])?\s+')


def _dependencies(text: str, package: str) -> list[str]:
    """Nested type names as written in `text` ('pkg/Name'), sorted like rosbag2's std::set."""
    deps = set()
    for m in _FIELD_TYPE_RE.finditer(text):
        token = m.group(1)
        if token in PRIMITIVES:
            continue
        if '/' not in token:
            token = 'std_msgs/Header' if token == 'Header' else f'{package}/{token}'
        deps.add(token)
    return sorted(deps)


def synthesized_text(mdef: MessageDef) -> str:
    """Field lines for a generated type that has no file (e.g. `_FeedbackMessage`)."""
    return ''.join(f'{f.type} {f.name}\n' for f in mdef.fields)


def _message_text(name: str, reg: Registry) -> str:
    """Text of a message named as written ('pkg/Name'), generated sub-types included."""
    pkg, _, short = normalize_name(name).split('/')
    for kind in ('msg', 'action', 'srv'):
        full = f'{pkg}/{kind}/{short}'
        if kind == 'msg' and reg.exists(full):
            return reg.interface_text(full)
        try:
            return synthesized_text(reg.message(full))
        except InterfaceError:
            continue
    raise UnknownInterfaceError(f"Unknown interface '{name}'")


def definition_text(name: str, reg: Registry) -> str:
    """Full `ros2msg` text for a message (or a service via `SRV:`, for service events)."""
    name = normalize_name(name)
    pkg, kind, short = name.split('/')
    seen: set[str] = set()

    def expand(text: str, package: str) -> str:
        out = text
        for dep in _dependencies(text, package):
            if dep in seen:
                continue
            seen.add(dep)
            dep_pkg = dep.split('/')[0]
            out += '\n' + SEPARATOR + f'MSG: {dep}\n' + expand(_message_text(dep, reg), dep_pkg)
        return out

    if kind == 'srv' and short.endswith('_Event') and reg.exists(name[: -len('_Event')]):
        name = name[: -len('_Event')]
    if kind == 'srv' and reg.exists(name):
        return SEPARATOR + f'SRV: {name}\n' + expand(reg.interface_text(name), pkg)
    reg.message(name)  # raises a clear error for unknown names
    if kind == 'msg' and reg.exists(name):
        return expand(reg.interface_text(name), pkg)
    return expand(synthesized_text(reg.message(name)), pkg)


@dataclass
class _Line:
    raw: str
    is_comment: bool = False
    trailing_comment: str | None = None
    nested: str | None = None


def _classify(raw: str, package: str) -> _Line:
    line = _Line(raw)
    if raw.strip() == SERVICE_SEPARATOR:
        return line
    code, comment = split_comment(raw)
    if not code.strip():
        line.is_comment = comment is not None
        return line
    item = parse_line(code, package)
    if isinstance(item, Constant):
        return line
    if comment is not None and comment.strip():
        line.trailing_comment = comment.strip()
    if not item.type.is_primitive:
        line.nested = item.type.base
    return line


def show_lines(
    name: str, reg: Registry, *, all_comments: bool = False, no_comments: bool = False
) -> list[str]:
    """Lines of `ros2 interface show`: nested types expanded with one tab per level."""
    parts = name.split('/')
    if len(parts) != 3:
        raise InterfaceError(f"Invalid name '{name}'. Expected three parts separated by '/'")
    out: list[str] = []

    def show(type_name: str, comments: bool, level: int) -> None:
        package = type_name.split('/')[0]
        path = reg.interface_path(type_name)
        text = path.read_text(encoding='utf-8')
        for lineno, raw in enumerate(text.splitlines(), start=1):
            raw = raw.rstrip()
            try:
                line = _classify(raw, package)
            except ValueError as e:
                raise InterfaceError(f'{path}:{lineno}: {e}') from None
            shown = raw
            if not comments:
                if not raw or line.is_comment:
                    shown = ''
                elif line.trailing_comment is not None:
                    shown = split_comment(raw)[0].strip()
                if shown:
                    out.append('\t' * level + shown)
            else:
                out.append('\t' * level + shown if shown else '')
            if line.nested:
                show(line.nested, all_comments, level + 1)

    show(name, all_comments or not no_comments, 0)
    return out


def proto_yaml(name: str, reg: Registry) -> str:
    """Default-valued YAML of a message, a service request or an action goal."""
    from .classes import get_interface
    from .convert import message_to_yaml

    name = normalize_name(name)
    kind = reg.kind_of(name)
    cls = get_interface(name, reg)
    if kind == 'service':
        cls = cls.Request
    elif kind == 'action':
        cls = cls.Goal
    return message_to_yaml(cls())
