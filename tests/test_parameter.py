"""`Parameter`: type inference, type/value agreement, message round trips, CLI value typing."""

from __future__ import annotations

import pytest

from ros2lite.interfaces import deserialize, serialize
from ros2lite.msgs.rcl_interfaces.msg import ParameterValue
from ros2lite.parameter import Parameter, get_parameter_value, parameter_value_to_python

T = Parameter.Type


@pytest.mark.parametrize(
    "value, type_",
    [
        (None, T.NOT_SET),
        (True, T.BOOL),
        (3, T.INTEGER),
        (2.5, T.DOUBLE),
        ("s", T.STRING),
        ([b"a"], T.BYTE_ARRAY),
        ([True], T.BOOL_ARRAY),
        ([1, 2], T.INTEGER_ARRAY),
        ((1.0,), T.DOUBLE_ARRAY),
        (["a"], T.STRING_ARRAY),
        ([], T.BYTE_ARRAY),
    ],
)
def test_type_inference(value: object, type_: Parameter.Type) -> None:
    assert Parameter("p", value=value).type_ == type_
    assert type_.check(value)


def test_type_and_value_must_agree() -> None:
    with pytest.raises(ValueError, match=r"Type 'Type\.DOUBLE' and value '1' do not agree"):
        Parameter("p", T.DOUBLE, 1)
    with pytest.raises(ValueError):
        Parameter("p", T.INTEGER, True)  # a bool is not a ROS integer
    with pytest.raises(TypeError, match="not one of the allowed types"):
        Parameter("p", value={"a": 1})
    with pytest.raises(TypeError, match="not a list of one of the allowed types"):
        Parameter("p", value=[1, "a"])
    with pytest.raises(TypeError, match="type must be an instance"):
        Parameter("p", 3)  # type: ignore[arg-type]


@pytest.mark.parametrize(
    "value",
    [True, -4, 0.5, "text", [b"\x00", b"\xff"], [False, True], [1, -2], [0.25], ["a", "b"], None],
)
def test_message_round_trip_over_cdr(value: object) -> None:
    msg = Parameter("name", value=value).to_parameter_msg()
    back = Parameter.from_parameter_msg(deserialize(type(msg), serialize(msg)))
    assert back.name == "name"
    assert back.type_ == Parameter.Type.from_parameter_value(value)
    expected = list(value) if isinstance(value, list) else value
    assert parameter_value_to_python(back.get_parameter_value()) == expected


@pytest.mark.parametrize(
    "text, type_, python",
    [
        ("true", T.BOOL, True),
        ("5", T.INTEGER, 5),
        ("1.5", T.DOUBLE, 1.5),
        ("hello", T.STRING, "hello"),
        ("[1, 2]", T.INTEGER_ARRAY, [1, 2]),
        ("[1.0, 2.5]", T.DOUBLE_ARRAY, [1.0, 2.5]),
        ("[a, b]", T.STRING_ARRAY, ["a", "b"]),
        ("[true, false]", T.BOOL_ARRAY, [True, False]),
        ("[1, a]", T.STRING, "[1, a]"),
        ("{a: 1}", T.STRING, "{a: 1}"),
        ("'3'", T.STRING, "3"),
        ("~", T.STRING, "~"),
        ("[", T.STRING, "["),
    ],
)
def test_command_line_values(text: str, type_: Parameter.Type, python: object) -> None:
    value = get_parameter_value(text)
    assert value.type == type_.value
    assert parameter_value_to_python(value) == python


def test_unknown_type_number() -> None:
    with pytest.raises(RuntimeError, match="unexpected parameter type 42"):
        parameter_value_to_python(ParameterValue(type=42))
