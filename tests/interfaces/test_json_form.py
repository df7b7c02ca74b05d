"""The JSON form (schema 1): exact round trips over the test_msgs definitions and the bundled
types, and the spellings the README promises (base64 bytes, "nan"/"inf", exact int64)."""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from ros2lite.interfaces import registry
from ros2lite.interfaces.classes import get_interface
from ros2lite.interfaces.errors import PopulateError
from ros2lite.interfaces.json_form import (
    dumps,
    json_to_message,
    message_to_json,
    value_to_json,
)

from .strategies import message

REG = registry.Registry([Path(__file__).parent / 'data', registry.BUNDLED])
TEST_MSGS = sorted(p.stem for p in (Path(__file__).parent / 'data/test_msgs/msg').glob('*.msg'))


def tm(name: str) -> Any:
    return get_interface(f'test_msgs/msg/{name}', REG)


def round_trip(msg: Any) -> Any:
    """Through text, as a pipe carries it."""
    text = dumps(message_to_json(msg))
    back = json_to_message(type(msg), json.loads(text))
    assert dumps(message_to_json(back)) == text
    return back


@pytest.mark.parametrize('name', TEST_MSGS)
def test_every_test_msgs_type_round_trips_with_its_defaults(name: str) -> None:
    round_trip(tm(name)())


def fill_extremes(m: Any) -> None:
    m.bool_values = [True, False, True]
    m.byte_values = [b'\x00', b'\x7f', b'\xff']
    m.char_values = [65, 0, 255]
    m.float32_values = [1.5, float('nan'), float('-inf')]
    m.float64_values = [1e300, float('inf'), -0.0]
    m.int8_values = [-128, 0, 127]
    m.uint8_values = [0, 128, 255]
    m.int64_values = [-(2**63), 2**53 + 1, 2**63 - 1]
    m.uint64_values = [0, 2**53 + 1, 2**64 - 1]
    m.string_values = ['a', '', 'ünï "quoted" \\ \n']


@pytest.mark.parametrize('name', ['Arrays', 'BoundedSequences', 'UnboundedSequences'])
def test_arrays_keep_extreme_values(name: str) -> None:
    m = tm(name)()
    fill_extremes(m)
    m.basic_types_values = [tm('BasicTypes')(int64_value=-(2**63), float64_value=math.nan)] * 3
    form = message_to_json(m)
    assert form['byte_values'] == 'AH//'  # base64 of 00 7f ff
    assert form['char_values'] == 'QQD/'
    assert form['uint8_values'] == 'AID/'
    assert form['float32_values'] == [1.5, 'nan', '-inf']
    assert form['float64_values'] == [1e300, 'inf', -0.0]
    assert form['uint64_values'] == [0, 2**53 + 1, 2**64 - 1]
    # the text carries the integers digit for digit, past 2^53
    assert '"int64_values":[-9223372036854775808,9007199254740993,9223372036854775807]' in dumps(
        form
    )
    back = round_trip(m)
    assert list(back.uint64_values) == [0, 2**53 + 1, 2**64 - 1]
    assert back.byte_values == [b'\x00', b'\x7f', b'\xff']
    assert math.isnan(back.float32_values[1]) and back.float64_values[1] == math.inf
    assert math.copysign(1, back.float64_values[2]) == -1
    assert back.basic_types_values[2].int64_value == -(2**63)


def test_empty_sequences_and_empty_byte_arrays() -> None:
    m = tm('UnboundedSequences')()
    form = message_to_json(m)
    assert form['bool_values'] == [] and form['byte_values'] == '' and form['uint8_values'] == ''
    assert form['basic_types_values'] == []
    assert round_trip(m).uint8_values.tolist() == []


def test_scalars_bytes_chars_nan_and_nesting() -> None:
    b = tm('BasicTypes')(
        byte_value=b'\xfe', char_value=200, float32_value=float('nan'), uint64_value=2**64 - 1
    )
    form = message_to_json(b)
    assert form['byte_value'] == 254 and form['char_value'] == 200
    assert form['float32_value'] == 'nan' and form['uint64_value'] == 2**64 - 1
    back = round_trip(b)
    assert back.byte_value == b'\xfe' and math.isnan(back.float32_value)
    multi = tm('MultiNested')()
    multi.unbounded_sequence_of_unbounded_sequences = [tm('UnboundedSequences')()]
    multi.unbounded_sequence_of_unbounded_sequences[0].int16_values = [-1, 2]
    back = round_trip(multi)
    assert back.unbounded_sequence_of_unbounded_sequences[0].int16_values.tolist() == [-1, 2]


def test_strings_and_wstrings() -> None:
    w = tm('WStrings')(
        wstring_value='ハローワールド ✓', unbounded_sequence_of_wstrings=['ä', '', '𝄞']
    )
    assert round_trip(w).unbounded_sequence_of_wstrings == ['ä', '', '𝄞']
    text = dumps(message_to_json(w))
    assert 'ハローワールド' in text  # UTF-8 kept, not \u escapes
    s = tm('Strings')(bounded_string_value='x' * 22)
    assert round_trip(s).bounded_string_value == 'x' * 22


def test_builtins_and_a_bundled_image() -> None:
    b = tm('Builtins')()
    b.time_value.sec = -5
    b.duration_value.nanosec = 999_999_999
    assert message_to_json(b) == {
        'duration_value': {'sec': 0, 'nanosec': 999_999_999},
        'time_value': {'sec': -5, 'nanosec': 0},
    }
    image = get_interface('sensor_msgs/msg/Image')(height=1, width=3, data=bytes(range(250, 253)))
    assert message_to_json(image)['data'] == '+vv8'
    assert bytes(round_trip(image).data) == bytes((250, 251, 252))


def test_field_values_and_placeholders() -> None:
    m = tm('UnboundedSequences')(uint8_values=[1, 2], float32_values=[math.inf])
    assert value_to_json(m.uint8_values) == 'AQI='
    assert value_to_json(m.float32_values) == ['inf']
    assert value_to_json(m.byte_values_default) == 'AAH/'
    assert value_to_json(m.basic_types_values) == []
    assert value_to_json(tm('BasicTypes')()) == message_to_json(tm('BasicTypes')())
    form = message_to_json(m, no_arr=True)
    assert form['uint8_values'] == '<sequence type: uint8, length: 2>'
    assert message_to_json(tm('Strings')(), no_str=True)['string_value'] == '<string length: <0>>'


def test_input_may_be_lists_and_other_infinity_spellings() -> None:
    m = json_to_message(
        tm('UnboundedSequences'),
        {'uint8_values': [1, 2], 'byte_values': [255], 'float64_values': ['-Infinity', 2]},
    )
    assert m.uint8_values.tolist() == [1, 2] and m.byte_values == [b'\xff']
    assert m.float64_values.tolist() == [-math.inf, 2.0]


@pytest.mark.parametrize(
    ('obj', 'reason'),
    [
        ({'uint8_values': 'not base64!'}, "field 'uint8_values' (uint8[]) takes base64 text"),
        # set_message_fields' own words (for a single float ros2cli's: "could not convert")
        ({'float32_values': ['NaN', 'big']}, "(float32[]) takes numbers; [nan, 'big']"),
        ({'int64_values': [1.5]}, "field 'int64_values' is a list of integers"),
        ({'nope': 1}, "object has no attribute 'nope'"),
        ({'bool_values': [True] * 4}, ''),
        ('[1]', 'a message is a JSON object, not list'),
        ('{"a": ', 'invalid JSON'),
    ],
)
def test_bad_input_is_one_line(obj: object, reason: str) -> None:
    cls = tm('BoundedSequences' if 'bool_values' in str(obj) else 'UnboundedSequences')
    with pytest.raises(PopulateError) as e:
        json_to_message(cls, obj)
    assert reason in str(e.value) and '\n' not in str(e.value)


BUNDLED = [
    'sensor_msgs/msg/Image',
    'sensor_msgs/msg/PointCloud2',
    'sensor_msgs/msg/JointState',
    'nav_msgs/msg/OccupancyGrid',
    'diagnostic_msgs/msg/DiagnosticArray',
    'visualization_msgs/msg/MarkerArray',
    'std_msgs/msg/Float32MultiArray',
]


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.sampled_from(BUNDLED).flatmap(message))
def test_random_bundled_messages_round_trip(msg: Any) -> None:
    round_trip(msg)
