"""Text forms of definitions: the rosbag2 `ros2msg` schema and `interface show` lines.

The schema text follows rosbag2's local definition source: the type's file verbatim, then every
dependency once (depth first, siblings sorted) after an 80-'=' line and `MSG: <name as written>`.
"""

from __future__ import annotations

import re
import textwrap
from dataclasses import dataclass

from .classes import Message, get_interface
from .convert import message_to_yaml
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


# rosidl_adapter takes exactly one bracketed span without a comma out of a comment as its unit
_UNIT_RE = re.compile(r'(\s*\[([^,\]]+)\])')


def _comment_annotation(comment: str) -> str | None:
    """What rosidl_adapter keeps of a one-line comment (None: nothing, which ros2cli then
    does not count as a comment): a lone '[unit]' taken out, then dedented."""
    units = _UNIT_RE.findall(comment)
    if len(units) == 1:
        comment = comment.replace(units[0][0], '')
    return textwrap.dedent(comment) if comment else None


@dataclass
class _Line:
    """One line of a definition file as ros2cli's `interface show` sees it: it hands each
    line alone to rosidl_adapter's parser, whose comment rules this follows (a whole-line
    comment starts in column 0; a trailing one is split at the first '#', quotes or not)."""

    raw: str
    is_comment: bool = False
    trailing_comment: str | None = None
    nested: str | None = None


def _classify(raw: str, package: str) -> _Line:
    line = _Line(raw)
    if raw.strip() == SERVICE_SEPARATOR:
        return line
    spaced = raw.replace('\t', ' ')
    if spaced.startswith('#'):
        line.is_comment = _comment_annotation(spaced.lstrip('#')) is not None
        return line
    code = split_comment(raw)[0]
    if not code.strip():
        return line  # empty, or indented comment: neither for rosidl_adapter
    item = parse_line(code, package)
    cut = spaced.find('#')
    if cut >= 0:
        line.trailing_comment = _comment_annotation(spaced[cut:].lstrip('#'))
    if not isinstance(item, Constant) and not item.type.is_primitive:
        line.nested = item.type.base
    return line


def _without_comment(line: _Line) -> str | None:
    """The line as `--no-comments` prints it; None when it is left out. A trailing comment is
    cut where its text first occurs in the line, one character before it, as ros2cli does."""
    text = line.raw
    if not text or line.is_comment:
        return None
    if line.trailing_comment is not None:
        text = text[: text.find(line.trailing_comment) - 1].strip()
    return text


def _file_lines(text: str) -> list[str]:
    """The lines as iterating over the opened file gives them (only '\n' ends one)."""
    lines = text.split('\n')
    if lines[-1] == '':
        lines.pop()
    return [line.rstrip() for line in lines]


def show_lines(
    name: str, reg: Registry, *, all_comments: bool = False, no_comments: bool = False
) -> list[str]:
    """Lines of `ros2 interface show`: nested types expanded with one tab per level. The
    top-level type shows its comments unless `no_comments`; nested ones only with
    `all_comments` (blank lines go with the comments)."""
    parts = name.split('/')
    if len(parts) != 3:
        raise InterfaceError(f"Invalid name '{name}'. Expected three parts separated by '/'")
    out: list[str] = []

    def show(type_name: str, comments: bool, level: int) -> None:
        package = type_name.split('/')[0]
        path, text = reg.interface_source(type_name)
        for lineno, raw in enumerate(_file_lines(text), start=1):
            try:
                line = _classify(raw, package)
            except ValueError as e:
                raise InterfaceError(f'{path}:{lineno}: {e}') from None
            shown = raw if comments else _without_comment(line)
            if shown is not None:
                out.append('\t' * level + shown if shown else '')
            if line.nested:
                show(line.nested, all_comments, level + 1)

    show(name, all_comments or not no_comments, 0)
    return out


def proto_yaml(name: str, reg: Registry) -> str:
    """Default-valued YAML of a message, a service request or an action goal."""
    return message_to_yaml(proto_message(name, reg))


def proto_message(name: str, reg: Registry) -> Message:
    """A default-valued message, service request or action goal (`interface proto`)."""
    name = normalize_name(name)
    kind = reg.kind_of(name)
    cls = get_interface(name, reg)
    if kind == 'service':
        cls = cls.Request
    elif kind == 'action':
        cls = cls.Goal
    message: Message = cls()
    return message
