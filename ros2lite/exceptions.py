"""The one base of every ros2lite error, and rclpy's exception names.

Every error the library raises on purpose derives from :class:`Ros2liteError`, so the CLI
(and a script) can tell "something the user can fix, said in one line" from a bug. Where an
rclpy name replaces a built-in exception, it also derives from that built-in, so code written
as ``except ValueError`` keeps working. Subpackages keep their own errors (``bag.errors``,
``interfaces.errors``, ``transport.errors``) under this base.
"""

from __future__ import annotations

import sys
from typing import Any, Protocol


class _TypeName(Protocol):
    """A parameter type (a member of `Parameter.Type`): what its name is."""

    @property
    def name(self) -> str: ...


class _ParameterTypes(Protocol):
    """`Parameter.Type` as this module needs it: which type a value maps to."""

    def from_parameter_value(self, parameter_value: object, /) -> _TypeName: ...


class _TypedParameter(Protocol):
    """What an error about a parameter reads of it: the shape of
    :class:`ros2lite.parameter.Parameter`, named here so that this base module imports none
    of the modules that raise its errors."""

    @property
    def Type(self) -> _ParameterTypes: ...  # Parameter's nested enum, read through the instance

    @property
    def name(self) -> str: ...

    @property
    def value(self) -> object: ...


class Ros2liteError(Exception):
    """Base of every error ros2lite raises on purpose; its message is one line for a user."""


class NotInitializedException(Ros2liteError, RuntimeError):
    """A node or entity was created before `ros2lite.init()` (rclpy's name)."""

    def __init__(self, message: str = 'ros2lite is not initialized: call ros2lite.init() first'):
        super().__init__(message)


class ROSInterruptException(Ros2liteError):
    """An operation was interrupted by the context shutting down (rclpy's name)."""


class InvalidHandle(Ros2liteError, RuntimeError):
    """An entity was used after it was destroyed (rclpy's name)."""


class NoTypeSupportImportedException(Ros2liteError, TypeError):
    """Something given as a message, service or action type is not one (rclpy's name)."""


# -- names -------------------------------------------------------------------------------------


class NameValidationException(Ros2liteError, ValueError):
    """A ROS name breaks rcl's rules; the message says which rule and where."""


class InvalidNamespaceException(NameValidationException):
    """A namespace is not a valid absolute ROS namespace."""


class InvalidNodeNameException(NameValidationException):
    """A node name is not a valid ROS node name."""


class InvalidTopicNameException(NameValidationException):
    """A topic name is not valid (before or after expansion)."""


class InvalidServiceNameException(NameValidationException):
    """A service name is not valid (before or after expansion)."""


# -- parameters --------------------------------------------------------------------------------


class ParameterException(Ros2liteError):
    """Base of every parameter error; the message ends with the parameter name(s)."""

    def __init__(self, error_msg: str, parameters: str | list[str]) -> None:
        super().__init__(f"{error_msg}: {parameters}")


class ParameterNotDeclaredException(ParameterException):
    """A parameter was used before being declared, and the node does not allow that."""

    def __init__(self, parameters: str | list[str]) -> None:
        super().__init__("Invalid access to undeclared parameter(s)", parameters)


class ParameterAlreadyDeclaredException(ParameterException):
    """A parameter was declared twice."""

    def __init__(self, parameters: str | list[str]) -> None:
        super().__init__("Parameter(s) already declared", parameters)


class InvalidParameterException(ParameterException):
    """The name cannot be a parameter name."""

    def __init__(self, parameter_name: str) -> None:
        super().__init__("Invalid parameter name", parameter_name)


class InvalidParameterTypeException(ParameterException):
    """A statically typed parameter was given a value of another type."""

    def __init__(self, desired_parameter: _TypedParameter, expected_type: str) -> None:
        # the Parameter's own Type enum names what it got (no import of ros2lite.parameter)
        got = desired_parameter.Type.from_parameter_value(desired_parameter.value).name
        super().__init__(
            f"Trying to set parameter '{desired_parameter.name}' to "
            f"'{desired_parameter.value}' of type '{got}', expecting type '{expected_type}'",
            desired_parameter.name,
        )


class InvalidParameterValueException(ParameterException):
    """A value was refused by a descriptor (range) or an on-set callback."""

    def __init__(self, parameter: str, value: object, reason: str) -> None:
        super().__init__(
            f"Invalid parameter value ({value}) for parameter. Reason: {reason}", parameter
        )


class ParameterImmutableException(ParameterException):
    """A read-only parameter cannot be changed or undeclared."""

    def __init__(self, parameter_name: str) -> None:
        super().__init__("Attempted to modify read-only parameter", parameter_name)


class ParameterUninitializedException(ParameterException):
    """A statically typed parameter was declared without a value and read before one came."""

    def __init__(self, parameter_name: str) -> None:
        super().__init__(f"The parameter '{parameter_name}' is not initialized", parameter_name)


# -- end of parameters -------------------------------------------------------------------------


def quiet_interrupt_exit() -> None:
    """From now on a Ctrl-C nobody caught ends this process without a traceback. Python
    still runs the `atexit` handlers and dies of SIGINT as usual (status 130 in a shell);
    only the printing is left out. For program start-up, where a Ctrl-C lands in an import
    before any code of ours can catch it, and for user code run by `ros2lite run` that
    lets one through (an `rclpy.init()` outside its `try`). Other exceptions print as ever."""
    if sys.excepthook is sys.__excepthook__:
        sys.excepthook = _quiet_interrupt_hook


def _quiet_interrupt_hook(kind: type[BaseException], error: BaseException, tb: Any) -> None:
    if issubclass(kind, KeyboardInterrupt):
        return
    sys.__excepthook__(kind, error, tb)
