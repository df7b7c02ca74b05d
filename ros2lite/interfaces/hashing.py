"""REP-2011 RIHS01 type hashes.

rmw_zenoh puts the hash in every key expression, so a single wrong byte here means a real ROS
node and ros2lite silently never meet. The table in shared/reference is the test oracle.
"""

from __future__ import annotations

import hashlib
import json
import weakref

from .parser import Field, FieldType
from .registry import Registry, default_registry, normalize_name

_TYPE_IDS = {
    'int8': 2,
    'uint8': 3,
    'int16': 4,
    'uint16': 5,
    'int32': 6,
    'uint32': 7,
    'int64': 8,
    'uint64': 9,
    'float32': 10,
    'float64': 11,
    'char': 3,
    'bool': 15,
    'byte': 16,
    'string': 17,
    'wstring': 18,
}
_NESTED = 1
_BOUNDED_STRING = {'string': 21, 'wstring': 22}
_CONTAINER_OFFSET = {'': 0, 'array': 48, 'bounded': 96, 'sequence': 144}
_DUMMY = Field('structure_needs_at_least_one_member', FieldType('uint8'))


def _field_type(ft: FieldType) -> dict[str, int | str]:
    if ft.is_primitive:
        base = _BOUNDED_STRING[ft.base] if ft.string_bound else _TYPE_IDS[ft.base]
        nested = ''
    else:
        base, nested = _NESTED, ft.base
    return {
        'type_id': base + _CONTAINER_OFFSET[ft.container],
        'capacity': ft.size,
        'string_capacity': ft.string_bound,
        'nested_type_name': nested,
    }


def _description(name: str, fields: list[Field]) -> dict[str, object]:
    return {
        'type_name': name,
        'fields': [{'name': f.name, 'type': _field_type(f.type)} for f in (fields or [_DUMMY])],
    }


def _top_fields(name: str, reg: Registry) -> list[Field]:
    """Fields of one description; services and actions are described as structs."""
    kind = reg.kind_of(name)
    if kind == 'service':
        return [
            Field('request_message', FieldType(name + '_Request')),
            Field('response_message', FieldType(name + '_Response')),
            Field('event_message', FieldType(name + '_Event')),
        ]
    if kind == 'action':
        return [
            Field('goal', FieldType(name + '_Goal')),
            Field('result', FieldType(name + '_Result')),
            Field('feedback', FieldType(name + '_Feedback')),
            Field('send_goal_service', FieldType(name + '_SendGoal')),
            Field('get_result_service', FieldType(name + '_GetResult')),
            Field('feedback_message', FieldType(name + '_FeedbackMessage')),
        ]
    return reg.message(name).fields


def type_description(name: str, reg: Registry | None = None) -> dict[str, object]:
    """The TypeDescription dict (without defaults) that the hash is computed over."""
    reg = reg or default_registry()
    name = normalize_name(name)
    top = _top_fields(name, reg)
    referenced: dict[str, list[Field]] = {}
    pending = [f.type.base for f in top if not f.type.is_primitive]
    while pending:
        dep = pending.pop()
        if dep in referenced:
            continue
        fields = _top_fields(dep, reg)
        referenced[dep] = fields
        pending += [f.type.base for f in fields if not f.type.is_primitive]
    return {
        'type_description': _description(name, top),
        'referenced_type_descriptions': [
            _description(n, referenced[n]) for n in sorted(referenced)
        ],
    }


# per registry, and dropped with it: keyed by id(), a registry made after another was freed
# (reload_registry) could reuse its id and be handed the old definitions' hashes
_CACHE: weakref.WeakKeyDictionary[Registry, dict[str, str]] = weakref.WeakKeyDictionary()


def type_hash(name: str, reg: Registry | None = None) -> str:
    """'RIHS01_<sha256 hex>' for a message, service, action or generated sub-type."""
    reg = reg or default_registry()
    cache = _CACHE.setdefault(reg, {})
    h = cache.get(name)
    if h is None:
        text = json.dumps(type_description(name, reg), separators=(', ', ': '), ensure_ascii=True)
        h = cache[name] = 'RIHS01_' + hashlib.sha256(text.encode()).hexdigest()
    return h


class TypeHash:
    """A type hash as rclpy holds it: a version and the raw hash bytes (`RIHS01_…` as text;
    'INVALID' when the version is unknown)."""

    __slots__ = ('_value', '_version')

    def __init__(self, version: int = -1, value: bytes = b'') -> None:
        self._version = version
        self._value = bytes(value)

    @property
    def version(self) -> int:
        """The hash version (1 for RIHS01; -1 unset)."""
        return self._version

    @property
    def value(self) -> bytes:
        """The raw hash bytes (32 for RIHS01)."""
        return self._value

    @classmethod
    def from_string(cls, text: str) -> TypeHash:
        """From `RIHS01_<64 hex digits>` (ValueError otherwise)."""
        prefix, _, digits = text.partition('_')
        if prefix != 'RIHS01' or len(digits) != 64:
            raise ValueError(f"not a RIHS01 type hash: '{text}'")
        return cls(version=1, value=bytes.fromhex(digits))

    def __str__(self) -> str:
        if self._version == 1:
            return 'RIHS01_' + self._value.hex()
        return 'INVALID'

    def __repr__(self) -> str:
        return f'TypeHash(version={self._version}, value={self._value!r})'

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, TypeHash):
            return NotImplemented
        return (self._version, self._value) == (other._version, other._value)

    def __hash__(self) -> int:
        return hash((self._version, self._value))
