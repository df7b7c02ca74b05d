"""YAML/CSV output and YAML/dict input, against ros2cli's documented formats."""

from __future__ import annotations

from typing import Any

import pytest

from ros2lite import interfaces as I
from ros2lite.interfaces.errors import PopulateError


def msg(name: str, **kwargs: object) -> Any:
    return I.get_interface(name)(**kwargs)


@pytest.mark.parametrize(
    ('value', 'text'),
    [
        ('Hello World: 1', "data: 'Hello World: 1'\n"),
        ('', "data: ''\n"),
        ('yes', "data: 'yes'\n"),
        ('123', "data: '123'\n"),
        ('plain', 'data: plain\n'),
    ],
)
def test_string_quoting(value: str, text: str) -> None:
    assert I.message_to_yaml(msg('std_msgs/msg/String', data=value)) == text


@pytest.mark.parametrize(
    ('value', 'text'),
    [
        (0.0, 'data: 0.0\n'),
        (2.5e-07, 'data: 2.5e-07\n'),
        (float('inf'), 'data: .inf\n'),
        (float('nan'), 'data: .nan\n'),
        (1e-07, 'data: 1.0e-07\n'),
    ],
)
def test_float_forms(value: float, text: str) -> None:
    assert I.message_to_yaml(msg('std_msgs/msg/Float64', data=value)) == text


def test_float32_is_widened_after_the_wire() -> None:
    data = I.serialize(msg('std_msgs/msg/Float32', data=0.1))
    out = I.deserialize('std_msgs/msg/Float32', data)
    assert I.message_to_yaml(out) == 'data: 0.10000000149011612\n'


def test_nested_block_and_flow_style() -> None:
    twist = msg('geometry_msgs/msg/Twist')
    twist.linear.x = 2.0
    assert I.message_to_yaml(twist) == (
        'linear:\n  x: 2.0\n  y: 0.0\n  z: 0.0\nangular:\n  x: 0.0\n  y: 0.0\n  z: 0.0\n'
    )
    # --flow-style flows sequences (and all inside them); mappings stay block as in ros2cli
    assert (
        I.message_to_yaml(msg('std_msgs/msg/String', data='Hello World: 1'), flow_style=True)
        == "data: 'Hello World: 1'\n"
    )
    seq = msg('std_msgs/msg/Int32MultiArray', data=[1, 2])
    assert I.message_to_yaml(seq) == ('layout:\n  dim: []\n  data_offset: 0\ndata:\n- 1\n- 2\n')
    path = msg('nav_msgs/msg/Path', poses=[msg('geometry_msgs/msg/PoseStamped')])
    for fast in (True, False):
        text = I.message_to_yaml(path, flow_style=True, fast=fast)
        assert text.startswith('header:\n  stamp:\n    sec: 0\n'), text
        assert text.endswith(
            "poses: [{header: {stamp: {sec: 0, nanosec: 0}, frame_id: ''}, pose: {position: "
            '{x: 0.0, y: 0.0, z: 0.0}, orientation: {x: 0.0, y: 0.0, z: 0.0, w: 1.0}}}]\n'
        ), text


def test_truncation_and_placeholders() -> None:
    arr = msg('std_msgs/msg/Float64MultiArray', data=[float(i) for i in range(5)])
    assert I.message_to_yaml(arr, truncate_length=2).endswith("data:\n- 0.0\n- 1.0\n- '...'\n")
    assert (
        I.message_to_yaml(msg('std_msgs/msg/String', data='abcdef'), truncate_length=3)
        == 'data: abc...\n'
    )
    assert "data: '<sequence type: double, length: 5>'" in I.message_to_yaml(arr, no_arr=True)
    imu = msg('sensor_msgs/msg/Imu')
    assert "orientation_covariance: '<array type: double[9]>'" in I.message_to_yaml(
        imu, no_arr=True
    )
    bounded = msg('rcl_interfaces/msg/ParameterDescriptor')
    assert (
        "floating_point_range: '<sequence type: rcl_interfaces/msg/FloatingPointRange[1], "
        "length: 0>'" in I.message_to_yaml(bounded, no_arr=True)
    )
    assert (
        I.message_to_yaml(msg('std_msgs/msg/String', data='hey'), no_str=True)
        == "data: '<string length: <3>>'\n"
    )


def test_csv() -> None:
    scan = msg('sensor_msgs/msg/LaserScan', ranges=[1.0, 2.0, 3.0])
    scan.header.frame_id = 'laser'
    assert I.message_to_csv(scan) == '0,0,laser,0.0,0.0,0.0,0.0,0.0,0.0,0.0,1.0,2.0,3.0,'
    assert I.message_to_csv(scan, truncate_length=2).endswith(',1.0,2.0,...,')
    assert I.message_to_csv(msg('std_msgs/msg/Bool', data=True)) == 'True'
    assert I.message_to_csv(scan, no_arr=True).endswith(
        '<sequence type: float, length: 3>,<sequence type: float, length: 0>'
    )


def test_csv_writes_a_separator_only_after_something() -> None:
    # rosidl_runtime_py adds ',' only when the text so far is not empty: an empty sequence
    # or a message without fields in first place leaves no column; later ones leave one
    arr = msg('std_msgs/msg/Int32MultiArray', data=[1, 2])
    assert I.message_to_csv(arr) == '0,1,2'
    assert I.message_to_csv(msg('std_msgs/msg/Int32MultiArray')) == '0,'
    goals = msg('nav_msgs/msg/Goals')
    assert I.message_to_csv(goals) == '0,0,,'


def test_dict() -> None:
    assert I.message_to_dict(msg('geometry_msgs/msg/Point', x=1.0)) == {
        'x': 1.0,
        'y': 0.0,
        'z': 0.0,
    }


def test_set_fields_coercions_and_nesting() -> None:
    twist = msg('geometry_msgs/msg/Twist')
    assert I.set_message_fields(twist, '{linear: {x: 2}, angular: {z: 1.8}}') == []
    assert twist.linear.x == 2.0 and twist.angular.z == 1.8
    num = msg('std_msgs/msg/Int32')
    I.set_message_fields(num, {'data': 7})  # a float is refused (the test below)
    assert num.data == 7
    text = msg('std_msgs/msg/String')
    I.set_message_fields(text, 'data: 5')
    assert text.data == '5'
    arr = msg('std_msgs/msg/Int32MultiArray')
    I.set_message_fields(arr, '{data: [1, 2, 3], layout: {dim: [{label: x, size: 3}]}}')
    assert list(arr.data) == [1, 2, 3] and arr.layout.dim[0].label == 'x'


@pytest.mark.parametrize(
    ('values', 'reason'),
    [
        ('{linear: 3}', "Value '3' is expected to be a dictionary but is a int"),
        ('{nope: 1}', "'Twist' object has no attribute 'nope'"),
        ('{linear: {x: abc}}', "could not convert string to float: 'abc'"),
        ('[1, 2]', "Value '[1, 2]' is expected to be a dictionary but is a list"),
        ('{linear: {x: [1', 'invalid YAML'),
    ],
)
def test_set_fields_errors(values: str, reason: str) -> None:
    with pytest.raises(PopulateError) as err:
        I.set_message_fields(msg('geometry_msgs/msg/Twist'), values)
    assert reason in str(err.value)


def test_a_float_for_an_integer_field_is_refused_as_rclpy_refuses_it() -> None:
    """rclpy's setter asserts an int; truncating 1.5 to 1 would send what nobody typed. An int
    for a float field stays fine."""
    for values, reason in [
        ({'data': 1.5}, "field 'data' is an integer (int32); 1.5 is not one"),
        ({'data': 2.0}, "field 'data' is an integer (int32); 2.0 is not one"),
    ]:
        with pytest.raises(PopulateError) as err:
            I.set_message_fields(msg('std_msgs/msg/Int32'), values)
        assert str(err.value) == reason
    with pytest.raises(PopulateError, match=r"list of integers \(uint8\[\]\); 0.5 is not one"):
        I.set_message_fields(msg('std_msgs/msg/UInt8MultiArray'), {'data': [1, 0.5]})
    twist = msg('geometry_msgs/msg/Twist')
    I.set_message_fields(twist, '{linear: {x: 1}}')
    assert twist.linear.x == 1.0 and isinstance(twist.linear.x, float)


def test_range_error_reads_like_rclpy() -> None:
    with pytest.raises(PopulateError, match=r"must be an integer in \[-128, 127\]"):
        I.set_message_fields(msg('std_msgs/msg/Int8'), {'data': 300})


def test_header_auto_and_stamp_now() -> None:
    pose = msg('geometry_msgs/msg/PoseStamped')
    setters = I.set_message_fields(pose, '{header: auto}', expand_header_auto=True)
    assert len(setters) == 1
    stamp = msg('builtin_interfaces/msg/Time', sec=5)
    setters[0](stamp)
    assert pose.header.stamp.sec == 5 and pose.header.frame_id == ''
    pose2 = msg('geometry_msgs/msg/PoseStamped')
    setters = I.set_message_fields(
        pose2, '{header: {stamp: now, frame_id: map}}', expand_time_now=True
    )
    assert len(setters) == 1 and pose2.header.frame_id == 'map'


# -- the libyaml fast path must be byte-identical to PyYAML's Python emitter -----------------

_TRICKY = [
    'yes',
    'no',
    'null',
    '~',
    '123',
    '1.5',
    '0x1f',
    '- a',
    'a: b',
    '#x',
    "it's",
    '"q"',
    ' lead',
    'trail ',
    '',
    '*a',
    '&b',
    '!t',
    '%p',
    '@x',
    '`y',
    '{',
    '[',
    ',',
    '?',
    '|',
]


def _ascii_message_strategy() -> Any:
    import string

    from hypothesis import strategies as st

    from ros2lite.interfaces.parser import INT_RANGES, FieldType
    from ros2lite.interfaces.registry import default_registry

    text = st.one_of(st.sampled_from(_TRICKY), st.text(string.printable.strip(), max_size=12))

    def value(ft: FieldType) -> Any:
        if ft.is_container:
            return st.lists(
                scalar(ft.element),
                min_size=ft.size if ft.container == 'array' else 0,
                max_size=ft.size if ft.container != 'sequence' else 4,
            )
        return scalar(ft)

    def scalar(ft: FieldType) -> Any:
        if ft.base == 'bool':
            return st.booleans()
        if ft.base == 'byte':
            return st.binary(min_size=1, max_size=1)
        if ft.base in INT_RANGES:
            return st.integers(*INT_RANGES[ft.base])
        if ft.base in ('float32', 'float64'):
            return st.floats(width=32 if ft.base == 'float32' else 64)
        if ft.base in ('string', 'wstring'):
            return text.filter(lambda s: not ft.string_bound or len(s) <= ft.string_bound)
        mdef = default_registry().message(ft.base)
        return st.builds(I.get_interface(ft.base), **{f.name: value(f.type) for f in mdef.fields})

    return scalar


FAST_NAMES = [n for n in I.list_interfaces() if '/msg/' in n]


@pytest.mark.parametrize('name', FAST_NAMES)
def test_fast_yaml_path_is_byte_identical(name: str) -> None:
    from hypothesis import HealthCheck, given, settings
    from hypothesis import strategies as st

    from ros2lite.interfaces.parser import FieldType

    strategy = _ascii_message_strategy()(FieldType(name))

    @settings(max_examples=8, deadline=None, suppress_health_check=list(HealthCheck))
    @given(st.data())
    def check(data: st.DataObject) -> None:
        m = data.draw(strategy)
        for flow in (False, True):
            for trunc in (None, 2):
                assert I.message_to_yaml(
                    m, flow_style=flow, truncate_length=trunc
                ) == I.message_to_yaml(m, flow_style=flow, truncate_length=trunc, fast=False)

    check()


# the CSV ros2cli 0.32.2 printed for this test_msgs/Arrays (the oracle's /t_arrays): 163
# columns; constants_values, three messages without fields, make one empty column in all
ARRAYS_CSV = (
    "True,False,True,b'\\x00',b'\\x7f',b'\\xff',65,0,127,1.5,nan,-0.0,1e+300,-inf,3.14159,"
    '-128,0,127,0,128,255,-32768,0,32767,0,1,65535,-2147483648,0,2147483647,0,1,4294967295,'
    '-9223372036854775808,0,9223372036854775807,0,1,18446744073709551615,a,,'
    'quote " and \' and : colon,False,b\'\\x00\',0,0.0,0.0,0,0,0,0,0,0,0,0,False,b\'\\x00\','
    "0,0.0,0.0,0,0,0,0,0,0,0,0,False,b'\\x00',0,0.0,0.0,0,0,0,0,0,0,0,0,,True,b'2',100,"
    "1.125,1.125,-50,200,-1000,2000,-30000,60000,-40000000,50000000,True,b'2',100,1.125,"
    "1.125,-50,200,-1000,2000,-30000,60000,-40000000,50000000,True,b'2',100,1.125,1.125,-50,"
    "200,-1000,2000,-30000,60000,-40000000,50000000,False,True,False,b'\\x00',b'\\x01',"
    "b'\\xff',0,1,127,1.125,0.0,-1.125,3.1415,0.0,-3.1415,0,127,-128,0,1,255,0,32767,-32768,"
    '0,1,65535,0,2147483647,-2147483648,0,1,4294967295,0,9223372036854775807,'
    '-9223372036854775808,0,1,18446744073709551615,max value,min value,0'
)


def test_csv_of_test_msgs_arrays_as_ros2cli_prints_it() -> None:
    from pathlib import Path

    from ros2lite.interfaces import registry
    from ros2lite.interfaces.classes import get_interface

    reg = registry.Registry([Path(__file__).parent / 'data', registry.BUNDLED])
    a = get_interface('test_msgs/msg/Arrays', reg)()
    a.bool_values = [True, False, True]
    a.byte_values = [b'\x00', b'\x7f', b'\xff']
    a.char_values = [65, 0, 127]
    a.float32_values = [1.5, float('nan'), -0.0]
    a.float64_values = [1e300, float('-inf'), 3.14159]
    a.int8_values = [-128, 0, 127]
    a.uint8_values = [0, 128, 255]
    a.int16_values = [-32768, 0, 32767]
    a.uint16_values = [0, 1, 65535]
    a.int32_values = [-2147483648, 0, 2147483647]
    a.uint32_values = [0, 1, 4294967295]
    a.int64_values = [-9223372036854775808, 0, 9223372036854775807]
    a.uint64_values = [0, 1, 18446744073709551615]
    a.string_values = ['a', '', 'quote " and \' and : colon']
    csv = I.message_to_csv(a)
    assert len(csv.split(',')) == 163
    assert csv == ARRAYS_CSV
