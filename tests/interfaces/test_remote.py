"""Types from a node's description: what the description service serves for local types
rebuilds the same types (same hash, same bytes) in a registry that has no files; a
description that does not fit its hash, or is hostile, is refused in one line."""

from __future__ import annotations

import pytest

from ros2lite.interfaces.cdr import codec
from ros2lite.interfaces.classes import get_interface
from ros2lite.interfaces.hashing import type_hash
from ros2lite.interfaces.registry import Registry, default_registry
from ros2lite.interfaces.remote import (
    MAX_TYPES,
    RemoteTypeError,
    assemble_action,
    description_hash,
    install,
)
from ros2lite.interfaces.text import definition_text, show_lines
from ros2lite.type_description_service import description_message, type_sources


@pytest.fixture(autouse=True)
def _fresh_cache(monkeypatch: pytest.MonkeyPatch) -> None:
    """Each test checks its own descriptions (the cache is by hash, for a process's life)."""
    from ros2lite.interfaces import remote

    monkeypatch.setattr(remote, '_FETCHED', {})


FieldMsg = get_interface('type_description_interfaces/msg/Field')
FieldTypeMsg = get_interface('type_description_interfaces/msg/FieldType')
Individual = get_interface('type_description_interfaces/msg/IndividualTypeDescription')
Description = get_interface('type_description_interfaces/msg/TypeDescription')


def _install(name: str, *, sources: bool, reg: Registry | None = None) -> Registry:
    reg = reg or Registry(roots=[])
    desc = description_message(name)
    install(name, type_hash(name), desc, type_sources(desc) if sources else [], 'node /n', reg)
    return reg


@pytest.mark.parametrize('sources', [True, False])
@pytest.mark.parametrize(
    'name',
    [
        'sensor_msgs/msg/PointCloud2',
        'diagnostic_msgs/msg/DiagnosticStatus',
        'std_msgs/msg/Empty',
        'sensor_msgs/msg/CameraInfo',
        'example_interfaces/action/Fibonacci_FeedbackMessage',
    ],
)
def test_messages_rebuilt_from_a_description(name: str, sources: bool) -> None:
    reg = _install(name, sources=sources)
    assert type_hash(name, reg) == type_hash(name)
    ours, theirs = get_interface(name)(), get_interface(name, reg)()
    assert codec(name, reg).serialize(theirs) == codec(name).serialize(ours)
    text = definition_text(name, reg)
    if sources:  # the node's files, comments and constants included
        assert text == definition_text(name, default_registry())
        constants = {k for k in vars(get_interface(name)) if k.isupper()}
        assert {k for k in vars(get_interface(name, reg)) if k.isupper()} == constants


def test_a_service_and_its_show_lines() -> None:
    name = 'example_interfaces/srv/AddTwoInts'
    for sources in (True, False):
        reg = _install(name, sources=sources)
        assert reg.kind_of(name) == 'service'
        assert show_lines(name, reg, no_comments=True) == ['int64 a', 'int64 b', '---', 'int64 sum']
        assert reg.interface_source(name)[0] == 'node /n'


def test_an_action_assembled_from_its_parts() -> None:
    name = 'example_interfaces/action/Fibonacci'
    alone = Registry(roots=[])
    for part in ('_SendGoal', '_GetResult', '_FeedbackMessage'):
        _install(name + part, sources=False, reg=alone)
    assert assemble_action(name, alone)
    assert type_hash(name, alone) == type_hash(name)


def _lying(name: str) -> object:
    desc = description_message(name)
    desc.type_description.fields.append(
        FieldMsg(name='extra', type=FieldTypeMsg(type_id=6))  # int32 extra
    )
    return desc


def test_a_description_that_does_not_hash_to_the_wire_hash() -> None:
    name = 'std_msgs/msg/ColorRGBA'
    with pytest.raises(RemoteTypeError, match='describes std_msgs/msg/ColorRGBA as RIHS01_'):
        install(name, type_hash(name), _lying(name), [], 'node /liar', Registry(roots=[]))


def test_sources_that_do_not_match_their_description() -> None:
    name = 'std_msgs/msg/ColorRGBA'
    desc = description_message(name)
    sources = type_sources(desc)
    sources[0].raw_file_contents = 'float32 r\nfloat32 g\n'
    with pytest.raises(RemoteTypeError, match='do not match its description'):
        install(name, type_hash(name), desc, sources, 'node /liar', Registry(roots=[]))


def _described(top: object, referenced: list[object]) -> tuple[object, str]:
    desc = Description(type_description=top, referenced_type_descriptions=referenced)
    return desc, description_hash(desc)


def _nested(name: str, ref: str) -> object:
    return Individual(
        type_name=name,
        fields=[FieldMsg(name='x', type=FieldTypeMsg(type_id=1, nested_type_name=ref))],
    )


@pytest.mark.parametrize(
    ('desc', 'why'),
    [
        (  # a type that contains itself: no codec could end
            _described(_nested('evil/msg/A', 'evil/msg/B'), [_nested('evil/msg/B', 'evil/msg/A')]),
            'contains itself',
        ),
        (
            _described(_nested('evil/msg/A', 'evil/msg/Gone'), []),
            'not described',
        ),
        (
            _described(
                _nested('evil/msg/A', 'evil/msg/T0'),
                [_nested(f'evil/msg/T{i}', 'std_msgs/msg/Empty') for i in range(MAX_TYPES + 1)],
            ),
            'too many',
        ),
        (  # a name that would become source text
            _described(
                Individual(
                    type_name='evil/msg/A',
                    fields=[FieldMsg(name='x=1;import os', type=FieldTypeMsg(type_id=6))],
                ),
                [],
            ),
            'invalid field name',
        ),
        (
            _described(
                Individual(
                    type_name='evil/msg/A',
                    fields=[FieldMsg(name='x', type=FieldTypeMsg(type_id=6 + 48, capacity=2**40))],
                ),
                [],
            ),
            'bad size',
        ),
        (
            _described(
                Individual(
                    type_name='evil/msg/A',
                    fields=[FieldMsg(name='x', type=FieldTypeMsg(type_id=250))],
                ),
                [],
            ),
            'unknown type id',
        ),
    ],
)
def test_hostile_descriptions_are_refused(desc: tuple[object, str], why: str) -> None:
    description, wire_hash = desc
    reg = Registry(roots=[])
    with pytest.raises(RemoteTypeError, match=why) as e:
        install('evil/msg/A', wire_hash, description, [], 'node /evil', reg)  # type: ignore[arg-type]
    assert '\n' not in str(e.value)
    assert not reg.exists('evil/msg/A')


def test_an_invalid_type_name_is_refused() -> None:
    desc, wire_hash = _described(Individual(type_name='evil/msg/../A', fields=[]), [])
    with pytest.raises(RemoteTypeError):
        install('evil/msg/../A', wire_hash, desc, [], 'node /evil', Registry(roots=[]))  # type: ignore[arg-type]


def test_a_type_whose_dependency_is_defined_differently_here() -> None:
    local = Registry(roots=[])
    local.add_definitions({'std_msgs/msg/Header': 'string frame_id\n'}, {}, 'a test')
    name = 'geometry_msgs/msg/PointStamped'
    with pytest.raises(RemoteTypeError, match='uses std_msgs/msg/Header, defined differently'):
        _install(name, sources=True, reg=local)
    assert not local.exists(name)


def test_sources_in_other_encodings_give_way_to_the_structure() -> None:
    name = 'std_msgs/msg/ColorRGBA'
    desc = description_message(name)
    sources = type_sources(desc)
    sources[0].encoding = 'idl'
    sources[0].raw_file_contents = 'module std_msgs { module msg { struct ColorRGBA {}; }; };'
    reg = Registry(roots=[])
    install(name, type_hash(name), desc, sources, 'node /idl', reg)
    assert reg.interface_text(name) == 'float32 r\nfloat32 g\nfloat32 b\nfloat32 a\n'
