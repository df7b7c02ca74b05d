"""Types no local package defines, taken from a node's own type description (REP-2011).

Every Jazzy node answers `~/get_type_description` with the full structure of a type it uses
(and, when asked, the definition files). This module is the pure half: a
`type_description_interfaces` TypeDescription and its TypeSources in, definitions in a
registry out, checked on the way: bounded and validated like any input from outside, and
hashed, so that the definitions built here hash to the RIHS01 the node announced on the wire.
A node that lies about a type gets one line, never a codec that decodes garbage. The service
call itself is a node's business (:mod:`ros2lite.remote_types`).

Kept in memory only, per hash: a fetch is one service call, and a disk cache would be one
more store of hostile input to bound and to keep from going stale.
"""

from __future__ import annotations

import hashlib
import json
from collections.abc import Sequence
from typing import NamedTuple, Protocol

from .classes import MAX_NESTING
from .errors import InterfaceError
from .hashing import type_hash
from .parser import (
    MAX_ARRAY_SIZE,
    MAX_BOUND,
    Field,
    FieldType,
    MessageDef,
    check_definition,
    validate_type_name,
)
from .registry import (
    ACTION_SUFFIXES,
    DEFINITION_LIMIT,
    SERVICE_SUFFIXES,
    Registry,
    default_registry,
)

__all__ = [
    'RemoteTypeError',
    'assemble_action',
    'description_hash',
    'fetched_from',
    'install',
]

# a description is input from outside: real ones hold a few dozen types of a few dozen fields
MAX_TYPES = 512
MAX_FIELDS = 1024
MAX_SOURCES_TOTAL = 4 * DEFINITION_LIMIT
_DUMMY_FIELD = 'structure_needs_at_least_one_member'

# type_description_interfaces/msg/FieldType ids, as the hash counts them (char is uint8)
_PRIMITIVE_IDS = {
    2: 'int8',
    3: 'uint8',
    4: 'int16',
    5: 'uint16',
    6: 'int32',
    7: 'uint32',
    8: 'int64',
    9: 'uint64',
    10: 'float32',
    11: 'float64',
    15: 'bool',
    16: 'byte',
    17: 'string',
    18: 'wstring',
    21: 'string',
    22: 'wstring',
}
_NESTED_ID = 1
_CONTAINERS = ('', 'array', 'bounded', 'sequence')


class RemoteTypeError(InterfaceError):
    """A type description a node served that cannot be used (one line says why)."""


class FieldTypeLike(Protocol):
    """type_description_interfaces/msg/FieldType as this module reads it."""

    type_id: int
    capacity: int
    string_capacity: int
    nested_type_name: str


class FieldLike(Protocol):
    """type_description_interfaces/msg/Field."""

    name: str
    type: FieldTypeLike


class IndividualLike(Protocol):
    """type_description_interfaces/msg/IndividualTypeDescription."""

    type_name: str
    fields: Sequence[FieldLike]


class DescriptionLike(Protocol):
    """type_description_interfaces/msg/TypeDescription."""

    type_description: IndividualLike
    referenced_type_descriptions: Sequence[IndividualLike]


class SourceLike(Protocol):
    """type_description_interfaces/msg/TypeSource."""

    type_name: str
    encoding: str
    raw_file_contents: str


def _hashable(desc: IndividualLike) -> dict[str, object]:
    return {
        'type_name': desc.type_name,
        'fields': [
            {
                'name': f.name,
                'type': {
                    'type_id': f.type.type_id,
                    'capacity': f.type.capacity,
                    'string_capacity': f.type.string_capacity,
                    'nested_type_name': f.type.nested_type_name,
                },
            }
            for f in desc.fields
        ],
    }


def description_hash(description: DescriptionLike) -> str:
    """RIHS01 of a description as it came (REP-2011's JSON form, defaults left out)."""
    tree = {
        'type_description': _hashable(description.type_description),
        'referenced_type_descriptions': [
            _hashable(d) for d in description.referenced_type_descriptions
        ],
    }
    text = json.dumps(tree, separators=(', ', ': '), ensure_ascii=True)
    return 'RIHS01_' + hashlib.sha256(text.encode()).hexdigest()


def _field_type(owner: str, f: FieldLike) -> FieldType:
    """Our FieldType of one described field (RemoteTypeError for ids or sizes we refuse)."""
    t = f.type
    container_index, base_id = divmod(t.type_id, 48)
    if container_index >= len(_CONTAINERS):
        raise RemoteTypeError(f'{owner}: field {f.name!r} has unknown type id {t.type_id}')
    container = _CONTAINERS[container_index]
    if base_id == _NESTED_ID:
        base = t.nested_type_name
        validate_type_name(base)
    elif base_id in _PRIMITIVE_IDS:
        base = _PRIMITIVE_IDS[base_id]
    else:
        raise RemoteTypeError(f'{owner}: field {f.name!r} has unknown type id {t.type_id}')
    bound = t.string_capacity if base_id in (21, 22) else 0
    size = t.capacity if container in ('array', 'bounded') else 0
    if (base_id in (21, 22)) != (t.string_capacity > 0) or not 0 <= bound <= MAX_BOUND:
        raise RemoteTypeError(f'{owner}: field {f.name!r} has a bad string bound')
    limit = MAX_ARRAY_SIZE if container == 'array' else MAX_BOUND
    if container in ('array', 'bounded') and not 1 <= size <= limit:
        raise RemoteTypeError(f'{owner}: field {f.name!r} has a bad size {t.capacity}')
    return FieldType(base, bound, container, size)


def _message_def(desc: IndividualLike) -> MessageDef:
    fields = [Field(f.name, _field_type(desc.type_name, f)) for f in desc.fields]
    if len(fields) == 1 and fields[0].name == _DUMMY_FIELD:
        fields = []  # how an empty message is described
    mdef = MessageDef(desc.type_name, fields)
    check_definition(mdef)
    return mdef


def _check_shape(name: str, description: DescriptionLike) -> dict[str, IndividualLike]:
    """The described types by name, refused when too many, badly named, referring to types
    they do not describe, or nested in a circle or too deep."""
    top = description.type_description
    if top.type_name != name:
        raise RemoteTypeError(f'the description is of {top.type_name!r}, not of {name}')
    every = [top, *description.referenced_type_descriptions]
    if len(every) > MAX_TYPES:
        raise RemoteTypeError(f'the description of {name} names {len(every)} types (too many)')
    by_name: dict[str, IndividualLike] = {}
    for d in every:
        validate_type_name(d.type_name)
        if d.type_name in by_name:
            raise RemoteTypeError(f'the description of {name} describes {d.type_name} twice')
        if len(d.fields) > MAX_FIELDS:
            raise RemoteTypeError(f'{d.type_name} has {len(d.fields)} fields (too many)')
        by_name[d.type_name] = d
    nested: dict[str, set[str]] = {}
    for d in every:
        refs = {f.type.nested_type_name for f in d.fields if f.type.type_id % 48 == _NESTED_ID}
        for ref in refs:
            if ref not in by_name:
                raise RemoteTypeError(f'{d.type_name} refers to {ref!r}, which is not described')
        nested[d.type_name] = refs
    depth: dict[str, int] = {}

    def visit(n: str, path: tuple[str, ...]) -> int:
        if n in path:
            raise RemoteTypeError(f'{n} contains itself (through {" → ".join(path)})')
        if n not in depth:
            below = [visit(r, (*path, n)) for r in nested[n]]
            depth[n] = 1 + max(below, default=0)
            if depth[n] > MAX_NESTING:
                raise RemoteTypeError(f'{name} nests types more than {MAX_NESTING} deep')
        return depth[n]

    visit(name, ())
    return by_name


# the fields hashing.py describes a service or an action file by (its top description)
_FILE_FIELDS = {
    'srv': (('request_message', 'response_message', 'event_message'), ('_Request', '_Response')),
    'action': (
        (
            'goal',
            'result',
            'feedback',
            'send_goal_service',
            'get_result_service',
            'feedback_message',
        ),
        ('_Goal', '_Result', '_Feedback'),
    ),
}


def _generated_from(name: str) -> list[str]:
    """The sub-type names a service or action file yields."""
    kind = name.split('/')[1]
    suffixes = SERVICE_SUFFIXES if kind == 'srv' else ACTION_SUFFIXES if kind == 'action' else ()
    return [name + s for s in suffixes]


def _field_lines(mdef: MessageDef) -> str:
    return ''.join(f'{f.type} {f.name}\n' for f in mdef.fields)


def build(
    name: str, description: DescriptionLike, sources: Sequence[SourceLike]
) -> tuple[dict[str, str], dict[str, MessageDef]]:
    """Definition texts ('pkg/kind/Name' → file text: the node's file where it sent one,
    else rebuilt from the structure) and the generated sub-types no text yields."""
    described = _check_shape(name, description)
    total = 0
    texts: dict[str, str] = {}
    for s in sources:
        # 'idl', 'dynamic', 'implicit' (or a file of another kind): built from the structure
        if s.type_name not in described or s.encoding != s.type_name.split('/')[1]:
            continue
        total += len(s.raw_file_contents)
        if len(s.raw_file_contents) > DEFINITION_LIMIT or total > MAX_SOURCES_TOTAL:
            raise RemoteTypeError(f'the definition files of {name} are too large')
        texts[s.type_name] = s.raw_file_contents
    structures = {n: _message_def(d) for n, d in described.items()}
    for n, mdef in structures.items():
        kind = n.split('/')[1]
        if n in texts:
            continue
        if kind == 'msg':
            texts[n] = _field_lines(mdef)
            continue
        top_fields, parts = _FILE_FIELDS[kind]
        if tuple(f.name for f in mdef.fields) == top_fields and all(
            n + p in structures for p in parts
        ):
            # a service or action file: rebuilt from its parts, which it refers to
            texts[n] = '---\n'.join(_field_lines(structures[n + p]) for p in parts)
    covered = {sub for n in texts for sub in _generated_from(n)}
    messages = {
        n: mdef
        for n, mdef in structures.items()
        if n not in texts and n not in covered and n.split('/')[1] != 'msg'
    }
    return texts, messages


def _check_parses(texts: dict[str, str], reg: Registry) -> None:
    """Every text parsed, those the type itself does not reach too."""
    for n in texts:
        kind = n.split('/')[1]
        if kind == 'msg':
            reg.message(n)
        elif kind == 'srv':
            reg.service(n)
        else:
            reg.action(n)


class _Checked(NamedTuple):
    """A description that passed: what it gave, and from where."""

    name: str
    origin: str
    texts: dict[str, str]
    messages: dict[str, MessageDef]


def _hash_or_none(name: str, reg: Registry) -> str | None:
    try:
        return type_hash(name, reg)
    except InterfaceError:
        return None


_FETCHED: dict[str, _Checked] = {}  # by wire hash, for this process's lifetime


def fetched_from(type_name: str, wire_hash: str) -> str | None:
    """Where a type with this hash was installed from in this process (None: it was not)."""
    found = _FETCHED.get(wire_hash)
    return found.origin if found is not None and found.name == type_name else None


def install(
    name: str,
    wire_hash: str,
    description: DescriptionLike,
    sources: Sequence[SourceLike],
    origin: str,
    reg: Registry | None = None,
) -> None:
    """Check a node's description of `name` against the hash it announced and add what the
    local search path lacks to `reg` (the default registry); RemoteTypeError says why not."""
    reg = reg or default_registry()
    known = _FETCHED.get(wire_hash)
    if known is not None and known.name == name:
        reg.add_definitions(known.texts, known.messages, known.origin)
        return
    got = description_hash(description)
    if got != wire_hash:
        raise RemoteTypeError(
            f'{origin} describes {name} as {got}, not as the {wire_hash} it announces'
        )
    alone = Registry(roots=[])
    try:
        texts, messages = build(name, description, sources)
        alone.add_definitions(texts, messages, origin)
        _check_parses(texts, alone)
        own = type_hash(name, alone)
    except RemoteTypeError:
        raise
    except InterfaceError as e:
        raise RemoteTypeError(f'{name} from {origin}: {e}') from None
    if own != wire_hash:
        raise RemoteTypeError(
            f'the definition files {origin} sends for {name} do not match its description'
        )
    for dep in sorted(set(texts) | set(messages)):
        if reg.exists(dep) and _hash_or_none(dep, reg) != type_hash(dep, alone):
            raise RemoteTypeError(f'{name} from {origin} uses {dep}, defined differently here')
    reg.add_definitions(texts, messages, origin)
    _FETCHED[wire_hash] = _Checked(name, origin, texts, messages)


def assemble_action(name: str, reg: Registry | None = None) -> bool:
    """An action file rebuilt from its goal, result and feedback once fetches of its services
    and feedback topic (each checked against its own hash) brought them; True if done."""
    reg = reg or default_registry()
    if reg.exists(name):
        return True
    parts = []
    for suffix in ('_Goal', '_Result', '_Feedback'):
        try:
            parts.append(reg.message(name + suffix))
        except InterfaceError:
            return False
    origin = next((c.origin for c in _FETCHED.values() if c.name.startswith(name)), 'the graph')
    reg.add_definitions({name: '---\n'.join(_field_lines(p) for p in parts)}, {}, origin)
    return True
