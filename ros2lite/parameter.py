"""Parameters as rclpy models them: a name, a type and a value that agree.

Code written for rclpy imports these names from here unchanged (`Parameter`, `Parameter.Type`,
`get_parameter_value`, `parameter_value_to_python`, `PARAMETER_SEPARATOR_STRING`).
"""

from __future__ import annotations

import array
import enum
from collections.abc import Iterable, Sequence
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from ros2lite.msgs.rcl_interfaces import msg as _rcl_msg

PARAMETER_SEPARATOR_STRING = "."

# ParameterValue's field for each type number (rcl_interfaces/msg/ParameterType)
_FIELDS = {
    1: "bool_value",
    2: "integer_value",
    3: "double_value",
    4: "string_value",
    5: "byte_array_value",
    6: "bool_array_value",
    7: "integer_array_value",
    8: "double_array_value",
    9: "string_array_value",
}
_SEQUENCES = (list, tuple, array.array)

AllowableParameterValue = (
    None
    | bool
    | int
    | float
    | str
    | Sequence[bytes]
    | Sequence[bool]
    | Sequence[int]
    | Sequence[float]
    | Sequence[str]
)
"""What a parameter can hold (rclpy's name): one value, or a list (tuple, array) of one kind."""


def _value_msg(type_number: int) -> _rcl_msg.ParameterValue:
    from ros2lite.interfaces import get_interface

    cls: type[_rcl_msg.ParameterValue] = get_interface("rcl_interfaces/msg/ParameterValue")
    return cls(type=type_number)


def _every(values: Iterable[object], kind: type) -> bool:
    # bool is an int to Python but never to ROS
    return all(isinstance(v, kind) and (kind is bool or not isinstance(v, bool)) for v in values)


class Parameter:
    """A named, typed value. `Parameter(name, value=v)` infers the type from the value."""

    class Type(enum.Enum):
        """rcl_interfaces/msg/ParameterType as an enum."""

        NOT_SET = 0
        BOOL = 1
        INTEGER = 2
        DOUBLE = 3
        STRING = 4
        BYTE_ARRAY = 5
        BOOL_ARRAY = 6
        INTEGER_ARRAY = 7
        DOUBLE_ARRAY = 8
        STRING_ARRAY = 9

        @classmethod
        def from_parameter_value(cls, parameter_value: object) -> Parameter.Type:
            """The type a Python value maps to; TypeError when it maps to none."""
            v = parameter_value
            if v is None:
                return cls.NOT_SET
            kinds: tuple[tuple[type, Parameter.Type], ...] = (
                (bool, cls.BOOL),
                (int, cls.INTEGER),
                (float, cls.DOUBLE),
                (str, cls.STRING),
            )
            for kind, member in kinds:
                if isinstance(v, kind):
                    return member
            if isinstance(v, _SEQUENCES):
                # the first kind every element has wins, as in rclpy (so [] is a byte array)
                kinds = (
                    (bytes, cls.BYTE_ARRAY),
                    (bool, cls.BOOL_ARRAY),
                    (int, cls.INTEGER_ARRAY),
                    (float, cls.DOUBLE_ARRAY),
                    (str, cls.STRING_ARRAY),
                )
                for kind, member in kinds:
                    if _every(v, kind):
                        return member
                raise TypeError(f"The given value is not a list of one of the allowed types '{v}'.")
            raise TypeError(f"The given value is not one of the allowed types '{v}'.")

        def check(self, parameter_value: object) -> bool:
            """Whether a parameter of this type can hold the value."""
            v = parameter_value
            kinds: dict[int, type] = {1: bool, 2: int, 3: float, 4: str}
            if self.value == 0:
                return v is None
            if self.value in kinds:
                return _every([v], kinds[self.value])
            if self.value == 5:
                return isinstance(v, (list, tuple)) and all(
                    isinstance(b, bytes) and len(b) == 1 for b in v
                )
            item = {6: bool, 7: int, 8: float, 9: str}[self.value]
            sequences = _SEQUENCES if self.value in (7, 8) else (list, tuple)
            return isinstance(v, sequences) and _every(v, item)

    def __init__(
        self,
        name: str,
        type_: Parameter.Type | None = None,
        value: AllowableParameterValue = None,
    ) -> None:
        if type_ is None:
            type_ = Parameter.Type.from_parameter_value(value)
        if not isinstance(type_, Parameter.Type):
            raise TypeError(f"type must be an instance of '{Parameter.Type!r}'")
        if not type_.check(value):
            raise ValueError(f"Type '{type_}' and value '{value}' do not agree")
        self._name = name
        self._type_ = type_
        self._value = value

    @property
    def name(self) -> str:
        """The parameter's full (dotted) name."""
        return self._name

    @property
    def type_(self) -> Parameter.Type:
        """Its type; NOT_SET for a parameter without a value."""
        return self._type_

    @property
    def value(self) -> Any:
        """Its value: whichever of the allowed kinds `type_` says (Any, as in rclpy, so that
        code reading a parameter it knows the type of needs no narrowing)."""
        return self._value

    def __repr__(self) -> str:
        return f"Parameter(name={self._name!r}, type_={self._type_}, value={self._value!r})"

    @classmethod
    def from_parameter_msg(cls, param_msg: _rcl_msg.Parameter) -> Parameter:
        """From an rcl_interfaces/msg/Parameter."""
        type_ = Parameter.Type(param_msg.value.type)
        field = _FIELDS.get(type_.value)
        value: Any = getattr(param_msg.value, field) if field else None  # a field, by name
        if value is not None and type_.value in (5, 6, 9):  # any sequence → list
            value = list(value)
        return cls(param_msg.name, type_, value)

    def get_parameter_value(self) -> _rcl_msg.ParameterValue:
        """This value as an rcl_interfaces/msg/ParameterValue."""
        msg = _value_msg(self._type_.value)
        field = _FIELDS.get(self._type_.value)
        if field:
            value = self._value
            setattr(msg, field, list(value) if isinstance(value, (tuple, array.array)) else value)
        return msg

    def to_parameter_msg(self) -> _rcl_msg.Parameter:
        """This parameter as an rcl_interfaces/msg/Parameter."""
        from ros2lite.interfaces import get_interface

        cls: type[_rcl_msg.Parameter] = get_interface("rcl_interfaces/msg/Parameter")
        return cls(name=self._name, value=self.get_parameter_value())


def parameter_value_to_python(parameter_value: _rcl_msg.ParameterValue) -> AllowableParameterValue:
    """The Python value held by an rcl_interfaces/msg/ParameterValue (None when not set)."""
    if parameter_value.type not in _FIELDS:
        if parameter_value.type == 0:
            return None
        raise RuntimeError(f"unexpected parameter type {parameter_value.type}")
    value: AllowableParameterValue = getattr(parameter_value, _FIELDS[parameter_value.type])
    return list(value) if isinstance(value, _SEQUENCES) else value


def get_parameter_value(string_value: str) -> _rcl_msg.ParameterValue:
    """The ParameterValue a command-line string stands for, typed the YAML way.

    Lists of one element type become arrays; a YAML string is that string (so "'5'" is the
    text 5); anything else (mixed lists, maps, null) is the text as written — what rclpy's
    `ros2 param set` sends.
    """
    from ros2lite.util.safe_yaml import YamlInputError, load

    try:
        loaded = load(string_value, "the value")
    except YamlInputError:
        loaded = string_value
    if isinstance(loaded, list) and not loaded:  # [] holds no type: rclpy sends bool[]
        return _value_msg(Parameter.Type.BOOL_ARRAY.value)
    if isinstance(loaded, (bool, int, float)) or (
        isinstance(loaded, list) and any(_every(loaded, k) for k in (bool, int, float, str))
    ):
        return Parameter("", value=loaded).get_parameter_value()
    text = loaded if isinstance(loaded, str) else string_value
    msg = _value_msg(Parameter.Type.STRING.value)
    msg.string_value = text
    return msg


__all__ = [
    "PARAMETER_SEPARATOR_STRING",
    "AllowableParameterValue",
    "Parameter",
    "get_parameter_value",
    "parameter_value_to_python",
]
