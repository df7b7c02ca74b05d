"""Message ⇄ JSON object, exact both ways (schema version 1, documented in the README).

Scripts and agents read `--json` output and feed it back to `topic pub`, so the form must keep
every value: integers stay JSON numbers (Python's json writes int64/uint64 exactly), floats
are written shortest-exact, and what JSON cannot carry is spelled so it comes back —
nan/inf/-inf as the strings "nan", "inf", "-inf", and uint8[]/char[]/byte[] arrays as one
base64 string (rosbridge's and Foxglove's choice: a camera image stays one short string, not
a million numbers). A lone `byte` or `char` is a number. The reverse turns those spellings
back into values and fills the message through `set_message_fields`, so bad input gets the
same one-line reasons as YAML input.
"""

from __future__ import annotations

import base64
import binascii
import json
import math
from array import array
from collections.abc import Mapping

from .classes import Message, field_class
from .convert import abbreviate_array, field_slots, set_message_fields
from .errors import PopulateError
from .parser import FieldType, MessageDef
from .registry import Registry, default_registry, normalize_name

SCHEMA_VERSION = 1
"""Bumped whenever a value's JSON spelling changes (the README's schema section)."""

BYTE_ARRAY_BASES = frozenset(('uint8', 'char', 'byte'))
FLOAT_BASES = frozenset(('float32', 'float64'))
# what the reverse takes for a non-finite float: ours, and JavaScript's spellings
_NON_FINITE = {
    'nan': math.nan,
    'inf': math.inf,
    '+inf': math.inf,
    '-inf': -math.inf,
    'infinity': math.inf,
    '+infinity': math.inf,
    '-infinity': -math.inf,
}


def float_to_json(value: float) -> float | str:
    """A float as the schema writes it: itself when finite, else "nan"/"inf"/"-inf"."""
    if math.isfinite(value):
        return value
    if math.isnan(value):
        return 'nan'
    return 'inf' if value > 0 else '-inf'


def _bytes_of(value: object) -> bytes:
    """The raw bytes of a uint8[]/char[] (`array('B')`) or byte[] (list of 1-byte bytes)."""
    if isinstance(value, array):
        return value.tobytes()
    if isinstance(value, (bytes, bytearray)):
        return bytes(value)
    assert isinstance(value, (list, tuple))
    return b''.join(v if isinstance(v, bytes) else bytes((v,)) for v in value)


def _scalar(value: object) -> object:
    if isinstance(value, float):
        return float_to_json(value)
    if isinstance(value, bytes):  # a lone byte
        return value[0] if len(value) == 1 else base64.b64encode(value).decode('ascii')
    if isinstance(value, Message):
        return message_to_json(value)
    return value


def value_to_json(
    value: object, ft: FieldType | None = None, *, no_arr: bool = False, no_str: bool = False
) -> object:
    """One field's value in the schema's form; `ft` (the field's type, when known) tells an
    empty byte array ("") from an empty list. `no_arr`/`no_str` put `topic echo`'s
    placeholder strings where arrays/strings were (such output no longer round-trips)."""
    if isinstance(value, Message):
        return message_to_json(value, no_arr=no_arr, no_str=no_str)
    if isinstance(value, (list, tuple, array, bytes, bytearray)) and (
        ft is None or ft.is_container
    ):
        if no_arr and ft is not None:
            return abbreviate_array(value, ft)
        if (ft is not None and ft.base in BYTE_ARRAY_BASES) or (
            ft is None
            and (
                (isinstance(value, array) and value.typecode == 'B')
                or isinstance(value, (bytes, bytearray))
                or (isinstance(value, list) and value and all(type(v) is bytes for v in value))
            )
        ):
            return base64.b64encode(_bytes_of(value)).decode('ascii')
        if isinstance(value, array):
            items: list[object] = value.tolist()
            if value.typecode in 'fd' and not math.isfinite(sum(value)):
                # some item is nan/inf (a finite sum says none is; C speed for a scan)
                return [float_to_json(v) for v in value]
            return items
        return [
            value_to_json(v, ft.element if ft else None, no_arr=no_arr, no_str=no_str)
            for v in value
        ]
    if no_str and isinstance(value, str):
        return f'<string length: <{len(value)}>>'
    return _scalar(value)


def message_to_json(
    msg: Message, *, no_arr: bool = False, no_str: bool = False
) -> dict[str, object]:
    """The message as a json.dumps-ready dict, keys the ROS field names in definition order."""
    return {
        name: value_to_json(getattr(msg, '_' + name), ft, no_arr=no_arr, no_str=no_str)
        for name, ft in field_slots(type(msg))
    }


def dumps(obj: object) -> str:
    """One compact JSON document (one NDJSON line): UTF-8 text kept, no NaN literals (the
    schema spells them as strings, so a bare NaN here is a bug, not output)."""
    return json.dumps(obj, ensure_ascii=False, allow_nan=False, separators=(',', ':'))


def echo_record(
    message: object,
    info: Mapping[str, object] | None = None,
    topic: str | None = None,
) -> object:
    """One echoed message as `topic echo --json` and `bag echo --json` both print it, so a
    bag replays to the same lines as the live topic: the message alone; with message info
    `{"message", "info"}`; from one of several topics `{"topic", "message", "info"}`."""
    if topic is not None:
        return {'topic': topic, 'message': message, 'info': dict(info or {})}
    if info is not None:
        return {'message': message, 'info': dict(info)}
    return message


def _float_from_json(name: str, value: object) -> object:
    """A float field's "nan"/"inf" spelling as its value; any other string goes on to
    set_message_fields, whose error is ros2cli's own ("could not convert string to float")."""
    if isinstance(value, str):
        return _NON_FINITE.get(value.strip().lower(), value)
    return value


def _bytes_from_json(name: str, ft: FieldType, value: object) -> object:
    if not isinstance(value, str):
        return value  # a list of numbers is fine too
    try:
        return base64.b64decode(value.encode('ascii'), validate=True)
    except (binascii.Error, UnicodeEncodeError, ValueError):
        shown = value if len(value) <= 40 else value[:37] + '...'
        raise PopulateError(
            f"field '{name}' ({ft}) takes base64 text or a list of numbers, not {shown!r}"
        ) from None


def _field_from_json(cls: type[Message], name: str, ft: FieldType, value: object) -> object:
    if ft.is_container and ft.base in BYTE_ARRAY_BASES:
        return _bytes_from_json(name, ft, value)
    if ft.base in FLOAT_BASES:
        if ft.is_container and isinstance(value, (list, tuple)):
            try:
                array('d', value)  # numbers only: nothing to turn back (C speed for a scan)
            except TypeError:
                return [_float_from_json(name, v) for v in value]
            return value
        if not ft.is_container:
            return _float_from_json(name, value)
        return value
    if ft.is_primitive:
        return value
    sub = field_class(cls, name)
    if ft.is_container and isinstance(value, (list, tuple)):
        return [json_to_fields(sub, v) if isinstance(v, Mapping) else v for v in value]
    if not ft.is_container and isinstance(value, Mapping):
        return json_to_fields(sub, value)
    return value


def json_to_fields(cls: type[Message], obj: Mapping[str, object]) -> dict[str, object]:
    """The schema's JSON object turned into what `set_message_fields` takes (base64 to bytes,
    "nan"/"inf" strings to floats, recursively); keys it does not know are left for
    set_message_fields to report."""
    types = dict(field_slots(cls))
    out: dict[str, object] = {}
    for name, value in obj.items():
        ft = types.get(name)
        out[name] = value if ft is None else _field_from_json(cls, name, ft, value)
    return out


def json_to_message(cls: type[Message], obj: object) -> Message:
    """A new message of `cls` filled from the schema's JSON object (parsed, or JSON text).

    Raises PopulateError with a one-line reason."""
    if isinstance(obj, str):
        try:
            obj = json.loads(obj)
        except json.JSONDecodeError as e:
            raise PopulateError(f'invalid JSON: {e}') from None
    if not isinstance(obj, Mapping):
        raise PopulateError(f'a message is a JSON object, not {type(obj).__name__}')
    msg = cls()
    set_message_fields(msg, json_to_fields(cls, obj))
    return msg


# -- definitions (`interface show --json`) -------------------------------------------------


def _default_json(value: object) -> object:
    if isinstance(value, float):
        return float_to_json(value)
    if isinstance(value, (list, tuple)):
        return [_default_json(v) for v in value]
    return value


def _message_def_json(mdef: MessageDef, nested: list[str]) -> dict[str, object]:
    fields: list[dict[str, object]] = []
    for f in mdef.fields:
        ft = f.type
        if not ft.is_primitive and ft.base not in nested:
            nested.append(ft.base)
        fields.append(
            {
                'name': f.name,
                'type': ft.base,
                'string_bound': ft.string_bound or None,
                'container': ft.container or None,
                'size': ft.size if ft.container in ('array', 'bounded') else None,
                'default': _default_json(f.default),
            }
        )
    constants = [
        {'name': c.name, 'type': c.type, 'value': _default_json(c.value)} for c in mdef.constants
    ]
    return {'name': mdef.name, 'fields': fields, 'constants': constants}


def definition_to_json(name: str, reg: Registry | None = None) -> dict[str, object]:
    """A type's parsed definition as data: its parts (a message's fields and constants; a
    service's request/response; an action's goal/result/feedback) and, under "types", each
    message type they nest, once, by name. Field "type" is a primitive name or
    'pkg/msg/Name'; "container" is null, "array" (T[N]), "bounded" (T[<=N]) or "sequence"
    (T[]); comments are not kept (the text form has them)."""
    reg = reg if reg is not None else default_registry()
    name = normalize_name(name)
    kind = reg.kind_of(name)
    nested: list[str] = []
    doc: dict[str, object] = {'name': name, 'kind': kind}
    if kind == 'service':
        svc = reg.service(name)
        doc['request'] = _message_def_json(svc.request, nested)
        doc['response'] = _message_def_json(svc.response, nested)
    elif kind == 'action':
        act = reg.action(name)
        doc['goal'] = _message_def_json(act.goal, nested)
        doc['result'] = _message_def_json(act.result, nested)
        doc['feedback'] = _message_def_json(act.feedback, nested)
    else:
        message = _message_def_json(reg.message(name), nested)
        doc['fields'], doc['constants'] = message['fields'], message['constants']
    types: dict[str, object] = {}
    while nested:  # breadth first: every type nested anywhere, once
        base = nested.pop(0)
        if base not in types:
            types[base] = _message_def_json(reg.message(base), nested)
    doc['types'] = types
    return doc
