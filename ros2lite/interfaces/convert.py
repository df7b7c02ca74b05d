"""Message ⇄ dict/YAML/CSV with rosidl_runtime_py's semantics.

Scripts parse `topic echo` output, so the YAML must be what rosidl_runtime_py produces: PyYAML's
own emitter, field order from the definition, truncation with a trailing '...', and the
'<array type: …>' placeholders. Input follows set_message_fields: coerce with the field's type,
recurse into dicts, and report problems as one readable line.
"""

from __future__ import annotations

import sys
from array import array
from collections.abc import Callable, Mapping, Sized
from functools import cache, partial
from typing import TYPE_CHECKING, Any, TypedDict

from .classes import ROSIDL_NAMES, Message, checked_fields, field_class
from .errors import FieldError, PopulateError
from .parser import INT_RANGES, FieldType

if TYPE_CHECKING:
    import yaml


class FormatOptions(TypedDict, total=False):
    """How message_to_dict/yaml/csv abbreviate (`topic echo`'s --truncate-length, --no-arr,
    --no-str)."""

    truncate_length: int | None
    no_arr: bool
    no_str: bool


_Setter = Callable[[Message], None]
"""Stores a stamp (builtin_interfaces/Time) where 'auto'/'now' asked for one."""


def _element_name(ft: FieldType) -> str:
    if ft.base in ('string', 'wstring'):
        return ft.base
    if ft.is_primitive:
        return ROSIDL_NAMES.get(ft.base, ft.base)
    return ft.base


def abbreviate_array(value: Sized, ft: FieldType) -> str:
    """The '--no-arr' placeholder for a container value."""
    name = _element_name(ft)
    if ft.container == 'array':
        return f'<array type: {name}[{ft.size}]>'
    if ft.container == 'bounded':
        return f'<sequence type: {name}[{ft.size}], length: {len(value)}>'
    return f'<sequence type: {name}, length: {len(value)}>'


def _convert(
    value: Any, ft: FieldType | None, trunc: int | None, no_arr: bool, no_str: bool
) -> Any:
    if isinstance(value, bytes):
        if trunc is not None and len(value) > trunc:
            return ''.join(chr(c) for c in value[:trunc]) + '...'
        return ''.join(chr(c) for c in value)
    if isinstance(value, str):
        if no_str:
            return f'<string length: <{len(value)}>>'
        if trunc is not None and len(value) > trunc:
            return value[:trunc] + '...'
        return value
    if isinstance(value, (list, tuple, array)):
        if no_arr and ft is not None and ft.is_container:
            return abbreviate_array(value, ft)
        items = value.tolist() if isinstance(value, array) else value
        if trunc is not None and len(items) > trunc:
            return [_convert(v, None, trunc, no_arr, no_str) for v in items[:trunc]] + ['...']
        if isinstance(value, array):
            return items
        return [_convert(v, None, trunc, no_arr, no_str) for v in items]
    if isinstance(value, (bool, int, float)):
        return value
    if isinstance(value, Message):
        return message_to_dict(value, truncate_length=trunc, no_arr=no_arr, no_str=no_str)
    return value


@cache
def field_slots(cls: type[Message]) -> tuple[tuple[str, FieldType], ...]:
    """(name, type) of each field of a message class, in order; worked out once per class."""
    return tuple(zip(cls.get_fields_and_field_types(), cls.SLOT_TYPES, strict=True))


def field_type(parent: object, name: str) -> FieldType | None:
    """The type of field `name` of the message `parent` (None for anything else): what tells
    an empty byte array from an empty list when a value is printed alone."""
    if not isinstance(parent, Message):
        return None
    return dict(field_slots(type(parent))).get(name)


def message_to_dict(
    msg: Message, *, truncate_length: int | None = None, no_arr: bool = False, no_str: bool = False
) -> dict[str, object]:
    """Nested plain dict/list/scalar form of a message, in field order."""
    return {
        name: _convert(getattr(msg, '_' + name), ft, truncate_length, no_arr, no_str)
        for name, ft in field_slots(type(msg))
    }


_DUMPERS: dict[bool, type[yaml.SafeDumper]] = {}
_C_MAX_WIDTH = 2**31 - 1  # libyaml keeps the width in a C int


def _dumper(fast: bool = False) -> type[yaml.SafeDumper]:
    """A private Dumper (our dict representer never leaks into the user's PyYAML).

    `fast` picks libyaml's emitter when PyYAML has it; callers only ask for it when the
    output is known to be identical to the pure-Python emitter's (see `_plain`).
    """
    dumper = _DUMPERS.get(fast)
    if dumper is None:
        import yaml

        base = getattr(yaml, 'CSafeDumper', yaml.SafeDumper) if fast else yaml.SafeDumper

        class Dumper(base):  # type: ignore[valid-type,misc]
            pass

        def represent_dict(d: yaml.SafeDumper, data: dict[str, object]) -> yaml.MappingNode:
            # a node with no flow style of its own: mappings stay block whatever
            # default_flow_style says, so --flow-style flows only the sequences (and what is
            # inside them), as rosidl_runtime_py's representer does
            items = [(d.represent_data(k), d.represent_data(v)) for k, v in data.items()]
            return yaml.MappingNode('tag:yaml.org,2002:map', items)

        Dumper.add_representer(dict, represent_dict)
        dumper = _DUMPERS[fast] = Dumper
    return dumper


def _plain(value: object) -> bool:
    """True when every string inside is printable ASCII.

    libyaml and PyYAML's Python emitter only differ in how they escape unusual characters
    (non-BMP, private use, controls), so for such values libyaml's 5x faster output is
    byte-identical (a property test checks this on every message type).
    """
    if isinstance(value, str):
        return value.isascii() and value.isprintable()
    if isinstance(value, dict):
        return all(_plain(v) for v in value.values())
    if isinstance(value, list):
        return all(type(v) is float or type(v) is int or _plain(v) for v in value)
    return True


def message_to_yaml(
    msg: Message,
    *,
    truncate_length: int | None = None,
    no_arr: bool = False,
    no_str: bool = False,
    flow_style: bool = False,
    fast: bool = True,
) -> str:
    """YAML text exactly as `ros2 topic echo` prints a message."""
    data = message_to_dict(msg, truncate_length=truncate_length, no_arr=no_arr, no_str=no_str)
    return dict_to_yaml(data, flow_style=flow_style, fast=fast)


def dict_to_yaml(data: Mapping[str, object], *, flow_style: bool = False, fast: bool = True) -> str:
    """YAML text of a message's dict form (`message_to_dict`, perhaps edited, as `service
    echo` names event types), dumped exactly as rosidl_runtime_py dumps messages."""
    import yaml

    use_c = fast and _plain(data)
    return yaml.dump(
        data,
        Dumper=_dumper(use_c),
        allow_unicode=True,
        width=_C_MAX_WIDTH if use_c else sys.maxsize,
        default_flow_style=flow_style,
        sort_keys=False,
    )


def _joined(parts: list[str]) -> str:
    """Join as rosidl_runtime_py's CSV does: a separator only once something was written, so
    empty leading items (an empty sequence, a message without fields) leave no column."""
    out = ''
    for part in parts:
        out = out + ',' + part if out else part
    return out


def _csv_value(
    val: object, ft: FieldType | None, trunc: int | None, no_arr: bool, no_str: bool
) -> str:
    if isinstance(val, (list, tuple, array)):
        if no_arr and ft is not None and ft.is_container:
            return abbreviate_array(val, ft)
        parts: list[str] = []
        for i, v in enumerate(val):
            if trunc is not None and i >= trunc:
                parts.append('...')
                break
            parts.append(_csv_value(v, None, trunc, no_arr, no_str))
        return _joined(parts)
    if isinstance(val, Message):
        return message_to_csv(val, truncate_length=trunc, no_arr=no_arr, no_str=no_str)
    if no_str and isinstance(val, str):
        return f'<string length: <{len(val)}>>'
    if trunc is not None and isinstance(val, str) and len(val) > trunc:
        val = val[:trunc] + '...'
    elif trunc is not None and isinstance(val, bytes) and len(val) > trunc:
        val = val[:trunc] + b'...'
    return str(val)


def message_to_csv(
    msg: Message, *, truncate_length: int | None = None, no_arr: bool = False, no_str: bool = False
) -> str:
    """Comma-separated leaf values, depth first, as `ros2 topic echo --csv` prints them."""
    return _joined(
        [
            _csv_value(getattr(msg, '_' + name), ft, truncate_length, no_arr, no_str)
            for name, ft in field_slots(type(msg))
        ]
    )


def _has_float(value: object) -> bool:
    """Whether `value`, or an item of it, is a float (for an integer field, never fine)."""
    if isinstance(value, float):
        return True
    return isinstance(value, (list, tuple)) and any(isinstance(v, float) for v in value)


def value_to_csv(value: object) -> str:
    """One field's value as `ros2 topic echo --csv` writes it (a message or an array as its
    comma-joined leaves), for tools that print a few fields rather than whole messages."""
    return _csv_value(value, None, None, False, False)


def _coerce(current: Any, value: Any, ft: FieldType) -> Any:
    """Convert `value` towards the type of the field's current value, like rosidl does."""
    if ft.base in INT_RANGES and _has_float(value):
        # rclpy's setters assert an integer field gets an int; int(1.5) would quietly send 1
        raise TypeError('a float for an integer field')
    if isinstance(current, array):
        return array(current.typecode, value)
    if type(value) is type(current):
        return value
    if isinstance(current, bytes) and isinstance(value, int):
        return value
    return type(current)(value)


def _reason(name: str, value: object, ft: FieldType, e: Exception) -> str:
    """Why `value` does not fit field `name`, in the user's terms where Python's own words
    would say nothing to them (NaN to int, str to bytes, a string for an array); rosidl's
    own messages otherwise, as ros2cli prints them."""
    shown = repr(value) if len(repr(value)) <= 60 else repr(value)[:57] + '...'
    if isinstance(value, str) and ft.is_container:
        return f"field '{name}' is a list of {_element_name(ft)} ({ft}), not the string {shown}"
    if isinstance(value, str) and ft.base == 'byte':
        return f"field '{name}' is a byte (an integer 0-255 or one-byte bytes), not {shown}"
    if isinstance(value, float) and ft.base in INT_RANGES:
        return f"field '{name}' is an integer ({ft}); {shown} is not one"
    if ft.base in INT_RANGES and isinstance(value, (list, tuple)) and _has_float(value):
        first = next(v for v in value if isinstance(v, float))
        return f"field '{name}' is a list of integers ({ft}); {first!r} is not one"
    if isinstance(e, OverflowError):
        return f"field '{name}' ({ft}): {shown} is out of range"
    if isinstance(e, TypeError) and ft.is_container and ft.is_primitive and not ft.is_string:
        return f"field '{name}' ({ft}) takes numbers; {shown} holds something else"
    return str(e)


def _populate(
    msg: Message, values: object, setters: list[_Setter], header_auto: bool, time_now: bool
) -> None:
    if not isinstance(values, dict):
        raise PopulateError(
            f"Value '{values}' is expected to be a dictionary but is a {type(values).__name__}"
        )
    types = dict(field_slots(type(msg)))
    for name, value in values.items():
        if name not in types:
            raise PopulateError(f"'{type(msg).__name__}' object has no attribute '{name}'")
        ft = types[name]
        current = getattr(msg, name)
        if (
            header_auto
            and value == 'auto'
            and ft.base == 'std_msgs/msg/Header'
            and not ft.is_container
        ):
            setters.append(partial(setattr, current, 'stamp'))
            continue
        if (
            time_now
            and value == 'now'
            and ft.base == 'builtin_interfaces/msg/Time'
            and not ft.is_container
        ):
            setters.append(partial(setattr, msg, name))
            continue
        coerced: Any
        if isinstance(current, Message) and type(value) is not type(current):
            coerced = type(current)()
            _populate(coerced, value, setters, header_auto, time_now)
        else:
            try:
                coerced = _coerce(current, value, ft)
            except (TypeError, ValueError, OverflowError) as e:
                raise PopulateError(_reason(name, value, ft, e)) from None
        if ft.is_container and not ft.is_primitive:
            cls = field_class(type(msg), name)
            built = []
            for item in coerced:
                if isinstance(item, cls):
                    built.append(item)
                    continue
                sub = cls()
                _populate(sub, item, setters, header_auto, time_now)
                built.append(sub)
            coerced = built
        try:
            setattr(msg, name, coerced)
        except FieldError as e:
            raise PopulateError(str(e)) from None


def set_message_fields(
    msg: Message,
    values: Mapping[str, object] | str | None,
    *,
    expand_header_auto: bool = False,
    expand_time_now: bool = False,
) -> list[_Setter]:
    """Fill `msg` from a dict or YAML text; returns setters for 'auto'/'now' stamps.

    Raises PopulateError with a one-line reason; ros2cli prints it after
    'Failed to populate field: '.
    """
    if isinstance(values, str):
        from ros2lite.util.safe_yaml import YamlInputError, load

        try:
            values = load(values, 'the values')
        except YamlInputError as e:
            raise PopulateError(f'invalid YAML: {e.detail}' if e.syntax else str(e)) from None
    if values is None:
        values = {}

    setters: list[_Setter] = []
    with checked_fields():  # values from outside are checked whatever the default
        _populate(msg, values, setters, expand_header_auto, expand_time_now)
    return setters
