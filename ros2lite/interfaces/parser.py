"""Parse ROS 2 ``.msg``/``.srv``/``.action`` text into plain definition objects.

The definitions are data only: classes, codecs, hashes and text renderings are derived from them
elsewhere, so the grammar lives in exactly one place.
"""

from __future__ import annotations

import keyword
import re
from dataclasses import dataclass, field
from typing import Any

from .errors import InterfaceError

PRIMITIVES = frozenset(
    {
        'bool',
        'byte',
        'char',
        'int8',
        'uint8',
        'int16',
        'uint16',
        'int32',
        'uint32',
        'int64',
        'uint64',
        'float32',
        'float64',
        'string',
        'wstring',
    }
)
STRING_TYPES = frozenset({'string', 'wstring'})
INT_RANGES: dict[str, tuple[int, int]] = {
    'byte': (0, 255),
    'char': (0, 255),
    'int8': (-(2**7), 2**7 - 1),
    'uint8': (0, 2**8 - 1),
    'int16': (-(2**15), 2**15 - 1),
    'uint16': (0, 2**16 - 1),
    'int32': (-(2**31), 2**31 - 1),
    'uint32': (0, 2**32 - 1),
    'int64': (-(2**63), 2**63 - 1),
    'uint64': (0, 2**64 - 1),
}
FLOAT_TYPES = frozenset({'float32', 'float64'})

SERVICE_SEPARATOR = '---'
# CDR lengths are uint32, so no bound can exceed it; a fixed array is built in full by every
# constructor, so a definition (perhaps a bag's) may not ask for more elements than this
MAX_BOUND = 2**32 - 1
MAX_ARRAY_SIZE = 1 << 20

# names become generated source text: \Z, since `$` also matches before a final newline
_PKG_RE = re.compile(r'^[a-z][a-z0-9_]*\Z')
_TYPE_NAME_RE = re.compile(r'^[A-Z][A-Za-z0-9]*\Z')
_FIELD_RE = re.compile(r'^[a-z][a-z0-9_]*\Z')
_CONST_RE = re.compile(r'^[A-Z][A-Z0-9_]*\Z')
_TYPE_RE = re.compile(
    r'^(?P<base>[A-Za-z][A-Za-z0-9_]*(?:/[A-Za-z][A-Za-z0-9_]*){0,2})'
    r'(?:<=(?P<sbound>\d+))?'
    r'(?:\[(?P<arr>(?:<=)?\d*)\])?\Z'
)


_CONTAINERS = frozenset({'', 'array', 'bounded', 'sequence'})


@dataclass(frozen=True)
class FieldType:
    """The type of one field: a primitive or nested message, optionally in a container."""

    base: str  # primitive name, or 'pkg/msg/Name' for nested messages
    string_bound: int = 0  # 'string<=N' bound; 0 means unbounded
    container: str = ''  # '' | 'array' (T[N]) | 'bounded' (T[<=N]) | 'sequence' (T[])
    size: int = 0  # array length or sequence bound

    @property
    def is_primitive(self) -> bool:
        """Whether the element type is a primitive (not a message)."""
        return self.base in PRIMITIVES

    @property
    def is_string(self) -> bool:
        """Whether the element type is string or wstring."""
        return self.base in STRING_TYPES

    @property
    def is_container(self) -> bool:
        """Whether it is an array or a sequence."""
        return self.container != ''

    @property
    def element(self) -> FieldType:
        """The type of one element (the container dropped)."""
        return FieldType(self.base, self.string_bound)

    def base_text(self) -> str:
        """Element type as written in a .msg file ('pkg/Name' for messages)."""
        if self.is_primitive:
            return self.base + (f'<={self.string_bound}' if self.string_bound else '')
        pkg, _, name = self.base.split('/')
        return f'{pkg}/{name}'

    def __str__(self) -> str:
        suffix = {
            '': '',
            'array': f'[{self.size}]',
            'bounded': f'[<={self.size}]',
            'sequence': '[]',
        }[self.container]
        return self.base_text() + suffix


@dataclass(frozen=True)
class Field:
    """One field of a message: name, type and default."""

    name: str
    type: FieldType
    default: object = None  # parsed default value, None when the .msg gives none


@dataclass(frozen=True)
class Constant:
    """One constant of a message: name, primitive type and value."""

    name: str
    type: str  # a primitive type name
    value: object


@dataclass
class MessageDef:
    """A parsed message definition: its fields and constants."""

    name: str  # 'pkg/msg/Name' (or a generated 'pkg/srv/S_Request' …)
    fields: list[Field] = field(default_factory=list)
    constants: list[Constant] = field(default_factory=list)

    @property
    def package(self) -> str:
        """The package the type belongs to."""
        return self.name.split('/')[0]

    @property
    def short_name(self) -> str:
        """The type's name without package and kind."""
        return self.name.rsplit('/', 1)[1]


@dataclass
class ServiceDef:
    """A parsed service: its request and response messages."""

    name: str
    request: MessageDef
    response: MessageDef


@dataclass
class ActionDef:
    """A parsed action: its goal, result and feedback messages."""

    name: str
    goal: MessageDef
    result: MessageDef
    feedback: MessageDef


def split_comment(line: str) -> tuple[str, str | None]:
    """Split a line into code and comment, ignoring '#' inside quoted strings."""
    quote = ''
    for i, ch in enumerate(line):
        if quote:
            if ch == '\\':
                continue
            if ch == quote:
                quote = ''
        elif ch in '"\'':
            quote = ch
        elif ch == '#':
            return line[:i], line[i + 1 :]
    return line, None


def resolve_type_name(token: str, package: str) -> str:
    """Qualify a type reference the way rosidl does inside `package`."""
    parts = token.split('/')
    if len(parts) == 1:
        if token == 'Header':
            return 'std_msgs/msg/Header'
        return f'{package}/msg/{token}'
    if len(parts) == 2:
        return f'{parts[0]}/msg/{parts[1]}'
    return token


def parse_field_type(token: str, package: str) -> FieldType:
    """Parse a type token such as 'float64[<=3]', 'string<=8[]' or 'geometry_msgs/Point[]'."""
    m = _TYPE_RE.match(token)
    if not m:
        raise ValueError(f"invalid type '{token}'")
    base, sbound, arr = m.group('base'), m.group('sbound'), m.group('arr')
    if base in PRIMITIVES:
        if sbound is not None and base not in STRING_TYPES:
            raise ValueError(f"only strings can be bounded, not '{base}'")
        string_bound = int(sbound) if sbound is not None else 0
        if sbound is not None and string_bound == 0:
            raise ValueError(f"string bound must be positive in '{token}'")
        if string_bound > MAX_BOUND:
            raise ValueError(f"string bound {string_bound} exceeds {MAX_BOUND} in '{token}'")
    else:
        if sbound is not None:
            raise ValueError(f"invalid type '{token}'")
        base = resolve_type_name(base, package)
        pkg, kind, name = base.split('/')
        if not _PKG_RE.match(pkg) or kind != 'msg' or not _TYPE_NAME_RE.match(name):
            raise ValueError(f"invalid type name '{token}'")
        string_bound = 0
    if arr is None:
        return FieldType(base, string_bound)
    if arr == '':
        return FieldType(base, string_bound, 'sequence')
    if arr.startswith('<='):
        if arr == '<=':
            raise ValueError(f"missing sequence bound in '{token}'")
        bound = int(arr[2:])
        if bound > MAX_BOUND:
            raise ValueError(f"sequence bound {bound} exceeds {MAX_BOUND} in '{token}'")
        return FieldType(base, string_bound, 'bounded', bound)
    size = int(arr)
    if size == 0:
        raise ValueError(f"array size must be positive in '{token}'")
    if size > MAX_ARRAY_SIZE:
        raise ValueError(f"array size {size} exceeds {MAX_ARRAY_SIZE} in '{token}'")
    return FieldType(base, string_bound, 'array', size)


def _unquote(text: str) -> str:
    if len(text) >= 2 and text[0] == text[-1] and text[0] in '"\'':
        q = text[0]
        return text[1:-1].replace('\\' + q, q)
    return text


def parse_primitive_value(type_name: str, text: str, string_bound: int = 0) -> Any:
    """Parse one scalar default or constant value of a primitive type."""
    text = text.strip()
    if type_name == 'bool':
        low = text.lower()
        if low in ('true', '1'):
            return True
        if low in ('false', '0'):
            return False
        raise ValueError(f"'{text}' is not a bool (true/false/1/0)")
    if type_name in INT_RANGES:
        try:
            value = int(text, 0) if text.lower().startswith(('0x', '0o', '0b')) else int(text)
        except ValueError:
            raise ValueError(f"'{text}' is not an integer") from None
        lo, hi = INT_RANGES[type_name]
        if not lo <= value <= hi:
            raise ValueError(f'{value} is out of range for {type_name} [{lo}, {hi}]')
        return value
    if type_name in FLOAT_TYPES:
        try:
            return float(text)
        except ValueError:
            raise ValueError(f"'{text}' is not a number") from None
    if type_name in STRING_TYPES:
        unquoted = _unquote(text)
        if string_bound and len(unquoted) > string_bound:
            raise ValueError(f"string '{unquoted}' exceeds its bound {string_bound}")
        return unquoted
    raise ValueError(f"type '{type_name}' cannot have a value")


def _split_array_items(text: str) -> list[str]:
    """Split '[a, "b,c", d]' into items, honouring quotes."""
    inner = text.strip()
    if not (inner.startswith('[') and inner.endswith(']')):
        raise ValueError(f"array value must be in brackets: '{text}'")
    inner = inner[1:-1].strip()
    if not inner:
        return []
    items: list[str] = []
    cur: list[str] = []
    quote = ''
    for ch in inner:
        if quote:
            cur.append(ch)
            if ch == quote and (len(cur) < 2 or cur[-2] != '\\'):
                quote = ''
        elif ch in '"\'':
            quote = ch
            cur.append(ch)
        elif ch == ',':
            items.append(''.join(cur).strip())
            cur = []
        else:
            cur.append(ch)
    items.append(''.join(cur).strip())
    return items


def parse_default(ftype: FieldType, text: str) -> Any:
    """Parse a field default, including array defaults such as '[1, 2, 3]'."""
    if not ftype.is_primitive:
        raise ValueError('nested message fields cannot have default values')
    if not ftype.is_container:
        return parse_primitive_value(ftype.base, text, ftype.string_bound)
    values = [
        parse_primitive_value(ftype.base, item, ftype.string_bound)
        for item in _split_array_items(text)
    ]
    if ftype.container == 'array' and len(values) != ftype.size:
        raise ValueError(f'array default needs exactly {ftype.size} values, got {len(values)}')
    if ftype.container == 'bounded' and len(values) > ftype.size:
        raise ValueError(f'sequence default has {len(values)} values, bound is {ftype.size}')
    return values


# names a generated class cannot use for a field (its constructor's own parameter)
_RESERVED_FIELDS = frozenset({'self'})


def field_name_ok(name: str) -> bool:
    """The field-name rule, one place for the parser and for definitions built otherwise."""
    return (
        bool(_FIELD_RE.match(name))
        and '__' not in name
        and not name.endswith('_')
        and not keyword.iskeyword(name)
        and name not in _RESERVED_FIELDS
    )


def constant_name_ok(name: str) -> bool:
    """The constant-name rule (UPPER_CASE, no dunder)."""
    return bool(_CONST_RE.match(name)) and '__' not in name


_LINE_RE = re.compile(r'^\s*(?P<type>\S+)\s+(?P<rest>.*)$')


def parse_line(code: str, package: str) -> Field | Constant:
    """Parse one non-empty, comment-free line into a field or a constant."""
    m = _LINE_RE.match(code)
    if not m:
        raise ValueError(f"expected '<type> <name>', got '{code.strip()}'")
    type_token, rest = m.group('type'), m.group('rest').strip()
    ftype = parse_field_type(type_token, package)
    if '=' in rest:
        name, _, value = rest.partition('=')
        name = name.strip()
        if not constant_name_ok(name):
            raise ValueError(f"invalid constant name '{name}' (UPPER_CASE expected)")
        if not ftype.is_primitive or ftype.is_container:
            raise ValueError(f"constant '{name}' must have a primitive, non-array type")
        if ftype.is_string:
            return Constant(
                name,
                ftype.base,
                parse_primitive_value(ftype.base, value.strip(), ftype.string_bound),
            )
        return Constant(name, ftype.base, parse_primitive_value(ftype.base, value))
    name, _, default_text = rest.partition(' ')
    if '\t' in name:
        name, _, more = name.partition('\t')
        default_text = (more + ' ' + default_text).strip()
    default_text = default_text.strip()
    if not field_name_ok(name):
        if keyword.iskeyword(name) or name in _RESERVED_FIELDS:
            raise ValueError(f"field name '{name}' is reserved (a Python keyword)")
        raise ValueError(f"invalid field name '{name}' (lower_case expected)")
    default = parse_default(ftype, default_text) if default_text else None
    return Field(name, ftype, default)


def parse_message(
    text: str, name: str, source: str = '<string>', first_line: int = 1
) -> MessageDef:
    """Parse message text; `name` is the full type name, e.g. 'std_msgs/msg/String'. The name
    is checked first: it may come from a bag or the wire, and classes are generated from it."""
    package, _, _ = validate_type_name(name)
    msg = MessageDef(name)
    seen: set[str] = set()
    for lineno, raw in enumerate(text.splitlines(), start=first_line):
        code, _ = split_comment(raw)
        if not code.strip():
            continue
        try:
            item = parse_line(code, package)
        except ValueError as e:
            raise InterfaceError(f'{source}:{lineno}: {e}') from None
        if item.name in seen:
            raise InterfaceError(f"{source}:{lineno}: duplicate name '{item.name}'")
        seen.add(item.name)
        if isinstance(item, Constant):
            msg.constants.append(item)
        else:
            msg.fields.append(item)
    return msg


def _sections(text: str, count: int, source: str) -> list[tuple[str, int]]:
    """Split text at '---' lines into exactly `count` sections with their first line numbers."""
    sections: list[tuple[list[str], int]] = [([], 1)]
    for lineno, raw in enumerate(text.splitlines(), start=1):
        if split_comment(raw)[0].strip() == SERVICE_SEPARATOR:
            sections.append(([], lineno + 1))
        else:
            sections[-1][0].append(raw)
    if len(sections) != count:
        raise InterfaceError(
            f"{source}: expected {count - 1} '---' separator(s), found {len(sections) - 1}"
        )
    return [('\n'.join(lines), start) for lines, start in sections]


def parse_service(text: str, name: str, source: str = '<string>') -> ServiceDef:
    """Parse `.srv` text into its request and response definitions."""
    validate_type_name(name)
    (req, l1), (resp, l2) = _sections(text, 2, source)
    return ServiceDef(
        name,
        parse_message(req, name + '_Request', source, l1),
        parse_message(resp, name + '_Response', source, l2),
    )


def parse_action(text: str, name: str, source: str = '<string>') -> ActionDef:
    """Parse `.action` text into its goal, result and feedback definitions."""
    validate_type_name(name)
    (goal, l1), (result, l2), (feedback, l3) = _sections(text, 3, source)
    return ActionDef(
        name,
        parse_message(goal, name + '_Goal', source, l1),
        parse_message(result, name + '_Result', source, l2),
        parse_message(feedback, name + '_Feedback', source, l3),
    )


_SHORT_RE = re.compile(r'^[A-Z][A-Za-z0-9_]*\Z')
# longest type name accepted (ROS caps topic names at 255 characters; a type is shorter)
MAX_TYPE_NAME_LENGTH = 255


def _shown(text: str) -> str:
    """A name as an error message may quote it: printable, and not a page long."""
    if not text.isprintable():
        text = text.encode('unicode_escape').decode('ascii')
    return text if len(text) <= 80 else text[:77] + '...'


def validate_type_name(name: str) -> tuple[str, str, str]:
    """Split 'pkg/kind/Name' and check each part, raising InterfaceError on bad input.

    Every name from outside (a bag, the wire, the command line, a definition file) passes here
    before a class or codec is generated for it, so it can only ever be a plain identifier."""
    if not isinstance(name, str):
        raise InterfaceError(f'Invalid interface name {name!r}: not a string')
    shown = _shown(name)
    parts = name.split('/')
    if len(parts) != 3:
        raise InterfaceError(
            f"Invalid interface name '{shown}': expected 'package/msg|srv|action/Name'"
        )
    pkg, kind, short = parts
    if len(name) > MAX_TYPE_NAME_LENGTH:
        raise InterfaceError(
            f"Invalid interface name '{shown}': longer than {MAX_TYPE_NAME_LENGTH} characters"
        )
    if not _PKG_RE.match(pkg):
        why = f"package '{_shown(pkg)}' must be lower_case (a-z, 0-9, _), starting with a letter"
    elif kind not in ('msg', 'srv', 'action'):
        why = f"'{_shown(kind)}' is not one of msg, srv, action"
    elif not _SHORT_RE.match(short):
        why = f"'{_shown(short)}' must be CamelCase (A-Z, a-z, 0-9), starting with a capital letter"
    else:
        return pkg, kind, short
    raise InterfaceError(f"Invalid interface name '{shown}': {why}")


def check_definition(mdef: MessageDef) -> None:
    """Refuse a definition whose names could not be Python identifiers in generated code.

    The parser only makes valid ones; this guards definitions built by other means before any
    source text is generated from them."""
    validate_type_name(mdef.name)
    for f in mdef.fields:
        if not field_name_ok(f.name):
            raise InterfaceError(f"{mdef.name}: invalid field name {f.name!r}")
        if not f.type.is_primitive:
            validate_type_name(f.type.base)
        # bounds and sizes are written into the source as numbers: whole ints, nothing else
        ft = f.type
        if type(ft.size) is not int or type(ft.string_bound) is not int:
            raise InterfaceError(f"{mdef.name}: field {f.name!r} has a size that is not a number")
        if ft.container not in _CONTAINERS:
            raise InterfaceError(f"{mdef.name}: field {f.name!r} has no known container kind")
    for c in mdef.constants:
        if not constant_name_ok(c.name):
            raise InterfaceError(f"{mdef.name}: invalid constant name {c.name!r}")
