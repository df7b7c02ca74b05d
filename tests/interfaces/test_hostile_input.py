"""Names and bytes from outside: a type name can never reach generated code unchecked, and
decoding any bytes as any bundled type gives a message or a CdrError, nothing else."""

from __future__ import annotations

import contextlib

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from ros2lite.interfaces import InterfaceError
from ros2lite.interfaces.cdr import codec
from ros2lite.interfaces.classes import ClassFactory, get_interface
from ros2lite.interfaces.errors import CdrError
from ros2lite.interfaces.parser import (
    MessageDef,
    parse_message,
    validate_type_name,
)
from ros2lite.interfaces.registry import Registry, default_registry

BAD_NAMES = [
    '',
    'String',
    'std_msgs/String/',
    'std_msgs/msg/String/x',
    'std_msgs//String',
    'std_msgs/msg/',
    '/msg/String',
    'Std_msgs/msg/String',
    '1pkg/msg/String',
    'pkg-x/msg/String',
    'pkg/mesg/String',
    'pkg/msg/string',
    'pkg/msg/_String',
    'pkg/msg/9String',
    'pkg/msg/X;Y',
    'pkg/msg/X Y',
    'pkg/msg/X\nimport os',
    'pkg/msg/X(object):\n  pass\nclass Y',
    'pkg/msg/X.Y',
    'pkg/msg/X\x00',
    'pkg/msg/Ünïcode',
    "pkg/msg/X'",
    'pkg/msg/' + 'A' * 300,
    'pkg/msg/X/../../etc',
]


@pytest.mark.parametrize('name', BAD_NAMES)
def test_grammar_breaking_type_names_are_refused_clearly(name: str) -> None:
    for check in (
        validate_type_name,
        lambda n: parse_message('int32 a', n),
        get_interface,
    ):
        with pytest.raises(InterfaceError) as info:
            check(name)
        text = str(info.value)
        assert text.startswith('Invalid interface name'), text
        assert '\n' not in text and len(text) < 300


@pytest.mark.parametrize(
    'line, why',
    [
        ('int32 class', 'reserved'),
        ('int32 self', 'reserved'),
        ('int32 Bad', 'lower_case'),
        ('int32 a;b', 'lower_case'),
        ('float64[99999999999] big', 'exceeds'),
        ('float64[<=99999999999] big', 'exceeds'),
        ('string<=99999999999 big', 'exceeds'),
        ('pkg/X;Y field', 'invalid'),
        ("int32 X;import os=1", 'invalid constant name'),
    ],
)
def test_bad_definition_lines_are_refused(line: str, why: str) -> None:
    with pytest.raises(InterfaceError, match=why):
        parse_message(line, 'pkg/msg/Bad')


def test_a_definition_built_by_hand_is_checked_before_code_is_generated() -> None:
    from ros2lite.interfaces.parser import Field, FieldType

    evil = MessageDef('pkg/msg/Evil', [Field('a=__import__("os")', FieldType('int32'))])
    with pytest.raises(InterfaceError, match='invalid field name'):
        ClassFactory(default_registry())._build(evil)


def test_cdr_code_is_generated_from_checked_definitions_only() -> None:
    from ros2lite.interfaces.cdr_gen import build_deserializer, build_serializer
    from ros2lite.interfaces.parser import Field, FieldType

    evil = MessageDef('pkg/msg/Evil', [Field('a=__import__("os")', FieldType('int32'))])
    reg = _Types({})
    reg._messages['pkg/msg/Evil'] = evil
    for build in (build_serializer, build_deserializer):
        with pytest.raises(InterfaceError, match='invalid field name'):
            build('pkg/msg/Evil', reg)


def test_sizes_of_a_definition_built_by_hand_are_numbers() -> None:
    from ros2lite.interfaces.cdr_gen import build_serializer
    from ros2lite.interfaces.parser import Field, FieldType

    bound = FieldType('string', string_bound='1: __import__("os")')  # type: ignore[arg-type]
    size = FieldType('int32', container='array', size='2] + [__import__("os")')  # type: ignore[arg-type]
    for ft in (bound, size):
        reg = _Types({})
        reg._messages['pkg/msg/Evil'] = MessageDef('pkg/msg/Evil', [Field('a', ft)])
        with pytest.raises(InterfaceError, match='not a number'):
            build_serializer('pkg/msg/Evil', reg)
        with pytest.raises(InterfaceError, match='not a number'):
            ClassFactory(default_registry())._build(reg._messages['pkg/msg/Evil'])


class _Types(Registry):
    """A registry holding only the given definitions (what a bag brings)."""

    def __init__(self, defs: dict[str, str]) -> None:
        super().__init__(roots=[])
        for name, text in defs.items():
            self._messages[name] = parse_message(text, name)


def test_a_type_that_contains_itself_is_an_error_not_a_recursion() -> None:
    reg = _Types({'pkg/msg/A': 'pkg/B b', 'pkg/msg/B': 'pkg/A[] a'})
    with pytest.raises(InterfaceError, match=r"contains itself \(pkg/msg/A -> pkg/msg/B -> "):
        codec('pkg/msg/A', reg)


def test_nesting_is_bounded() -> None:
    defs = {f'pkg/msg/T{i}': f'pkg/T{i + 1} next' for i in range(200)}
    defs['pkg/msg/T200'] = 'int32 x'
    with pytest.raises(InterfaceError, match='nests deeper than'):
        codec('pkg/msg/T0', _Types(defs))


def test_fields_named_like_builtins_build_and_round_trip() -> None:
    """R-W15: a field named `property` broke the class body of every later field."""
    from ros2lite.interfaces.convert import message_to_yaml

    text = (
        'string property\nstring value\nint32 len\nfloat64 float\nstring[] list\n'
        'int32 isinstance\nint32 type\nint32 range\nint32 staticmethod\nint32 y'
    )
    reg = _Types({'pkg/msg/Prop': text})
    cls = ClassFactory(reg).message_class('pkg/msg/Prop')
    msg = cls(property='a', value='b', len=3, float=1.5, list=['x'], type=7, y=9)
    assert (msg.property, msg.value, msg.len, msg.float, msg.list, msg.y) == (
        'a',
        'b',
        3,
        1.5,
        ['x'],
        9,
    )
    c = codec('pkg/msg/Prop', reg)
    text = message_to_yaml(msg)
    assert text.startswith('property: a\nvalue: b\nlen: 3\n')
    assert message_to_yaml(c.deserialize(c.serialize(msg))) == text


def _bundled_messages() -> list[str]:
    reg = default_registry()
    names = []
    for name in reg.all_interfaces():
        kind = reg.kind_of(name)
        if kind == 'message':
            names.append(name)
        elif kind == 'service':
            names += [name + '_Request', name + '_Response']
        else:
            names += [name + '_Goal', name + '_Result', name + '_FeedbackMessage']
    return names


BUNDLED = _bundled_messages()


@settings(
    max_examples=600,
    deadline=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large],
)
@given(
    name=st.sampled_from(BUNDLED),
    header=st.sampled_from([b'\x00\x01\x00\x00', b'\x00\x00\x00\x00', b'']),
    body=st.binary(max_size=256)
    | st.lists(
        st.sampled_from([b'\xff\xff\xff\xff', b'\x00' * 4, b'\x01', b'\xff']), max_size=40
    ).map(b''.join),
)
def test_random_bytes_decode_to_a_message_or_a_cdr_error(
    name: str, header: bytes, body: bytes
) -> None:
    """Every bundled type, random and adversarial bytes (huge lengths), both decoders."""
    data = header + body
    c = codec(name)
    try:
        msg = c.deserialize(data)
    except CdrError:
        pass
    else:
        assert type(msg).__name__ == name.rsplit('/', 1)[1]
    with contextlib.suppress(CdrError):
        c.fast_deserializer()(data)


def test_every_bundled_type_rejects_payloads_without_a_header() -> None:
    for name in BUNDLED:
        c = codec(name)
        for data in (b'', b'\x00', b'\x00\x01\x00', b'\x01\x01\x00\x00'):
            with pytest.raises(CdrError):
                c.deserialize(data)


def test_a_name_with_a_trailing_newline_is_refused() -> None:
    from ros2lite.interfaces.parser import validate_type_name

    with pytest.raises(InterfaceError, match='CamelCase'):
        validate_type_name('foo_msgs/msg/Bar\n')
    with pytest.raises(InterfaceError):
        validate_type_name('foo_msgs\n/msg/Bar')


def test_values_and_names_that_source_text_would_trip_on() -> None:
    """Non-finite constants and defaults, and a field named like the builtin the generated
    constructor uses, build a working class (values are bound, not written as text)."""
    import math

    reg = _Types(
        {
            'pkg/msg/Odd': 'float64 BIG=inf\nfloat64 y nan\nfloat64[2] z [inf, 1.0]\n'
            'float32 range\nstring[2] names\nstring[] s ["a"]\n'
        }
    )
    cls = ClassFactory(reg)._build(reg.message('pkg/msg/Odd'))
    msg = cls()
    assert math.isinf(cls.BIG) and math.isnan(msg.y) and list(msg.z) == [math.inf, 1.0]
    assert msg.range == 0.0 and msg.names == ['', '']
    msg.s.append('b')
    assert cls().s == ['a']  # a default is a new object each time
