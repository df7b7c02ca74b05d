"""What a type checker knows about interface classes, as rclpy's `type_support` tells it.

Message, service and action classes are built at run time from their definitions, so the
library is generic in them through these protocols: `create_publisher(String, …)` gives a
`Publisher[String]`, `create_client(AddTwoInts, …)` a `Client[AddTwoInts.Request,
AddTwoInts.Response]` whose `call()` returns the response type. The classes themselves are
described to type checkers by the generated stubs of the bundled packages
(`ros2lite/msgs/<pkg>/<kind>/__init__.pyi`, see :mod:`ros2lite.interfaces.stubs`).

Nothing here runs: the protocols only describe the classes of :mod:`ros2lite.interfaces`.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any, ClassVar, Protocol, TypeVar

__all__ = [
    'Action',
    'ActionT',
    'FeedbackMessage',
    'FeedbackT',
    'GetResultResponse',
    'GoalT',
    'Msg',
    'MsgT',
    'ResultT',
    'Srv',
    'SrvEventT',
    'SrvRequestT',
    'SrvResponseT',
    'SrvT',
]


class Msg(Protocol):
    """Any message class: a ROS type name and its fields (instances are its messages)."""

    _TYPE_NAME: ClassVar[str]

    @classmethod
    def get_fields_and_field_types(cls) -> dict[str, str]:
        """Field name → rosidl type text, in definition order."""
        ...


MsgT = TypeVar('MsgT', bound=Msg)
"""The message type a publisher or subscription carries."""

SrvRequestT = TypeVar('SrvRequestT', bound=Msg)
"""A service's request message type."""
SrvResponseT = TypeVar('SrvResponseT', bound=Msg)
"""A service's response message type."""
SrvEventT = TypeVar('SrvEventT', bound=Msg)
"""A service's introspection event message type."""

GoalT = TypeVar('GoalT', bound=Msg)
"""An action's goal message type."""
ResultT = TypeVar('ResultT', bound=Msg)
"""An action's result message type."""
FeedbackT = TypeVar('FeedbackT', bound=Msg)
"""An action's feedback message type."""

# the protocols only hand their parameters out (read-only members), so they are covariant
_RequestT_co = TypeVar('_RequestT_co', bound=Msg, covariant=True)
_ResponseT_co = TypeVar('_ResponseT_co', bound=Msg, covariant=True)
_GoalT_co = TypeVar('_GoalT_co', bound=Msg, covariant=True)
_ResultT_co = TypeVar('_ResultT_co', bound=Msg, covariant=True)
_FeedbackT_co = TypeVar('_FeedbackT_co', bound=Msg, covariant=True)


class Srv(Protocol[_RequestT_co, _ResponseT_co]):
    """A service class: a namespace of its Request, Response and Event message classes.

    Members are read-only here so that a class whose `Request` is a type alias of the
    request class (as the generated stubs write it, which keeps `AddTwoInts.Request`
    usable in annotations) still matches."""

    _TYPE_NAME: ClassVar[str]

    @property
    def Request(self) -> type[_RequestT_co]:
        """The request message class."""
        ...

    @property
    def Response(self) -> type[_ResponseT_co]:
        """The response message class."""
        ...

    @property
    def Event(self) -> type[Msg]:
        """The service introspection event message class."""
        ...


SrvT = TypeVar('SrvT', bound=Srv[Any, Any])
"""A service class."""


class Action(Protocol[_GoalT_co, _ResultT_co, _FeedbackT_co]):
    """An action class: its Goal, Result and Feedback message classes, plus the services and
    the feedback message rcl_action builds it from (`Impl`, as rosidl generates it)."""

    _TYPE_NAME: ClassVar[str]

    @property
    def Goal(self) -> type[_GoalT_co]:
        """The goal message class."""
        ...

    @property
    def Result(self) -> type[_ResultT_co]:
        """The result message class."""
        ...

    @property
    def Feedback(self) -> type[_FeedbackT_co]:
        """The feedback message class."""
        ...


ActionT = TypeVar('ActionT', bound=Action[Any, Any, Any])
"""An action class."""


class GetResultResponse(Protocol[_ResultT_co]):
    """What an action client's get_result call answers: the final status and the result."""

    @property
    def status(self) -> int:
        """The goal's terminal status (action_msgs/GoalStatus values)."""
        ...

    @property
    def result(self) -> _ResultT_co:
        """The result the execute callback returned."""
        ...


class GoalId(Protocol):
    """A goal's id (unique_identifier_msgs/UUID is one), by its one field: the generated
    messages stand on this module's types, so it names none of them."""

    @property
    def uuid(self) -> Sequence[int]:
        """The 16 bytes of the id."""
        ...


class FeedbackMessage(Protocol[_FeedbackT_co]):
    """What an action client's feedback callback gets: the goal's id and its feedback."""

    @property
    def goal_id(self) -> GoalId:
        """The goal's id."""
        ...

    @property
    def feedback(self) -> _FeedbackT_co:
        """The feedback the server published."""
        ...
