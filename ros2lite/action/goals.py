"""What the action server and client share: names of the five sub-entities, goal UUIDs, the
goal state machine of rcl_action, and the server's table of goals (status array, cancel
selection, result retention).

Nothing here touches the transport, so the rules can be tested (and reused) on their own.
"""

from __future__ import annotations

import enum
import time
import uuid as _uuid
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from ros2lite.exceptions import Ros2liteError
from ros2lite.interfaces import get_interface
from ros2lite.interfaces.classes import ActionType
from ros2lite.names import NameValidationException, action_entity_name
from ros2lite.type_support import GoalId

if TYPE_CHECKING:
    from ros2lite.msgs.action_msgs import msg as _action_msgs_msg
    from ros2lite.msgs.action_msgs import srv as _action_msgs_srv
    from ros2lite.msgs.unique_identifier_msgs import msg as _uuid_msg
    from ros2lite.node import Node

# action_msgs is where the status values are defined; they are read from there, not repeated
GoalStatus: type[_action_msgs_msg.GoalStatus] = get_interface('action_msgs/msg/GoalStatus')
GoalInfo: type[_action_msgs_msg.GoalInfo] = get_interface('action_msgs/msg/GoalInfo')
GoalStatusArray: type[_action_msgs_msg.GoalStatusArray] = get_interface(
    'action_msgs/msg/GoalStatusArray'
)
CancelGoal: type[_action_msgs_srv.CancelGoal] = get_interface('action_msgs/srv/CancelGoal')
UUID: type[_uuid_msg.UUID] = get_interface('unique_identifier_msgs/msg/UUID')

ACTIVE_STATES = frozenset(
    {GoalStatus.STATUS_ACCEPTED, GoalStatus.STATUS_EXECUTING, GoalStatus.STATUS_CANCELING}
)
TERMINAL_STATES = frozenset(
    {GoalStatus.STATUS_SUCCEEDED, GoalStatus.STATUS_CANCELED, GoalStatus.STATUS_ABORTED}
)

_STATUS_NAMES = {
    GoalStatus.STATUS_ACCEPTED: 'ACCEPTED',
    GoalStatus.STATUS_EXECUTING: 'EXECUTING',
    GoalStatus.STATUS_CANCELING: 'CANCELING',
    GoalStatus.STATUS_SUCCEEDED: 'SUCCEEDED',
    GoalStatus.STATUS_CANCELED: 'CANCELED',
    GoalStatus.STATUS_ABORTED: 'ABORTED',
}


def status_name(status: int) -> str:
    """'SUCCEEDED', 'ABORTED', … as ros2cli prints a goal status; 'UNKNOWN' otherwise."""
    return _STATUS_NAMES.get(status, 'UNKNOWN')


# -- names ---------------------------------------------------------------------------------


def resolve_action_name(node: Node, name: str) -> str:
    """`name` resolved as the node resolves topics; a bad one is said to be an action name."""
    try:
        resolved: str = node.resolve_topic_name(name)
    except NameValidationException as e:
        raise type(e)(str(e).replace('invalid topic name', 'invalid action name', 1)) from None
    return resolved


# rcl_action's five sub-entities, in its order: (role, name under the action's, type: a
# suffix to the action type's name when it starts with '_', else a type name of its own)
_ENTITIES = (
    ('service', 'send_goal', '_SendGoal'),
    ('service', 'cancel_goal', 'action_msgs/srv/CancelGoal'),
    ('service', 'get_result', '_GetResult'),
    ('topic', 'feedback', '_FeedbackMessage'),
    ('topic', 'status', 'action_msgs/msg/GoalStatusArray'),
)


@dataclass(frozen=True)
class ActionNames:
    """Full names and types of the five entities rcl_action builds an action from: the
    send_goal, cancel_goal and get_result services' and the feedback and status topics'."""

    action: str
    action_type: str
    send_goal: str = field(init=False)
    cancel_goal: str = field(init=False)
    get_result: str = field(init=False)
    feedback: str = field(init=False)
    status: str = field(init=False)

    def __post_init__(self) -> None:
        for _role, entity, _type in _ENTITIES:
            object.__setattr__(self, entity, action_entity_name(self.action, entity))

    def entities(self) -> list[tuple[str, str, str]]:
        """(role, name, type) of each sub-entity; role 'service' or 'topic'."""
        return [
            (role, getattr(self, entity), self.action_type + kind if kind[0] == '_' else kind)
            for role, entity, kind in _ENTITIES
        ]


def action_type_name(action_type: type | str) -> str:
    """'pkg/action/Name' of an action class or of such a string ('pkg/Name' is accepted)."""
    if isinstance(action_type, str):
        parts = action_type.split('/')
        if len(parts) == 2:
            parts = [parts[0], 'action', parts[1]]
        if len(parts) != 3 or parts[1] != 'action' or not all(parts):
            raise ValueError(f"'{action_type}' is not an action type name")
        return '/'.join(parts)
    name = getattr(action_type, '_TYPE_NAME', '')
    if not name or name.split('/')[1] != 'action':
        raise TypeError(f'not an action type: {action_type!r}')
    return str(name)


def resolve_action_type(action_type: type | str) -> type[ActionType]:
    """The action class for a class or a type name."""
    if isinstance(action_type, str):
        found: type[ActionType] = get_interface(action_type_name(action_type))
        return found
    action_type_name(action_type)
    if not issubclass(action_type, ActionType):
        raise TypeError(f'not a ros2lite action type: {action_type!r}')
    return action_type


# -- goal ids ------------------------------------------------------------------------------


def new_goal_id() -> _uuid_msg.UUID:
    """A random (version 4) goal UUID message, as rclpy's ActionClient makes them."""
    return UUID(uuid=list(_uuid.uuid4().bytes))


def goal_key(goal_id: GoalId | bytes | Sequence[int]) -> bytes:
    """The 16 bytes of a UUID message (or of bytes/list), usable as a dict key."""
    if isinstance(goal_id, (bytes, bytearray, Sequence)):
        return bytes(goal_id)
    return bytes(goal_id.uuid)


def goal_id_hex(goal_id: GoalId | bytes | Sequence[int]) -> str:
    """32 lower-case hex digits, as `ros2 action send_goal` prints a goal ID."""
    return goal_key(goal_id).hex()


# -- the goal state machine ----------------------------------------------------------------


class GoalEvent(enum.Enum):
    """What may happen to a goal (rcl_action's goal events)."""

    EXECUTE = 0
    CANCEL_GOAL = 1
    SUCCEED = 2
    ABORT = 3
    CANCELED = 4


_TRANSITIONS: dict[tuple[int, GoalEvent], int] = {
    (GoalStatus.STATUS_ACCEPTED, GoalEvent.EXECUTE): GoalStatus.STATUS_EXECUTING,
    (GoalStatus.STATUS_ACCEPTED, GoalEvent.CANCEL_GOAL): GoalStatus.STATUS_CANCELING,
    (GoalStatus.STATUS_EXECUTING, GoalEvent.CANCEL_GOAL): GoalStatus.STATUS_CANCELING,
    (GoalStatus.STATUS_EXECUTING, GoalEvent.SUCCEED): GoalStatus.STATUS_SUCCEEDED,
    (GoalStatus.STATUS_EXECUTING, GoalEvent.ABORT): GoalStatus.STATUS_ABORTED,
    (GoalStatus.STATUS_CANCELING, GoalEvent.SUCCEED): GoalStatus.STATUS_SUCCEEDED,
    (GoalStatus.STATUS_CANCELING, GoalEvent.ABORT): GoalStatus.STATUS_ABORTED,
    (GoalStatus.STATUS_CANCELING, GoalEvent.CANCELED): GoalStatus.STATUS_CANCELED,
}


class InvalidGoalTransition(Ros2liteError, RuntimeError):
    """An event that the goal's current state does not allow (e.g. succeed() before
    execute()); rclpy raises a RuntimeError here too."""


def next_state(state: int, event: GoalEvent) -> int:
    """The state `event` moves a goal in `state` to (InvalidGoalTransition if none)."""
    try:
        return _TRANSITIONS[(state, event)]
    except KeyError:
        raise InvalidGoalTransition(
            f'Failed to update goal state: goal in state {status_name(state)} can not take '
            f'event {event.name}'
        ) from None


def is_cancelable(state: int) -> bool:
    """Whether a goal in `state` may still take a cancel request."""
    return (state, GoalEvent.CANCEL_GOAL) in _TRANSITIONS


# -- the server's goals --------------------------------------------------------------------


@dataclass
class GoalEntry:
    """One accepted goal as the server tracks it until its result expires."""

    info: _action_msgs_msg.GoalInfo  # id and acceptance stamp
    state: int = GoalStatus.STATUS_ACCEPTED
    ended_at: float | None = None  # time.monotonic() when its result became known
    stamp_ns: int = field(init=False)

    def __post_init__(self) -> None:
        self.stamp_ns = self.info.stamp.sec * 1_000_000_000 + self.info.stamp.nanosec

    @property
    def key(self) -> bytes:
        """The goal id's 16 bytes."""
        return goal_key(self.info.goal_id)


class GoalTable:
    """Accepted goals in acceptance order, with rcl_action's bookkeeping rules.

    Not thread-safe on its own: the action server holds its lock around every call.
    """

    def __init__(self, result_timeout: float) -> None:
        self.result_timeout = result_timeout
        self._goals: dict[bytes, GoalEntry] = {}

    def __contains__(self, key: bytes) -> bool:
        return key in self._goals

    def __len__(self) -> int:
        return len(self._goals)

    def get(self, key: bytes) -> GoalEntry | None:
        """The entry of a goal id, if it is still tracked."""
        return self._goals.get(key)

    def add(self, info: _action_msgs_msg.GoalInfo) -> GoalEntry:
        """Track a newly accepted goal (RuntimeError if its id is taken)."""
        entry = GoalEntry(info)
        if entry.key in self._goals:
            raise RuntimeError(f'goal {entry.key.hex()} already exists')
        self._goals[entry.key] = entry
        return entry

    def update(self, key: bytes, event: GoalEvent) -> int:
        """Apply an event; returns the new state (raises InvalidGoalTransition)."""
        entry = self._goals[key]
        entry.state = next_state(entry.state, event)
        return entry.state

    def finish(self, key: bytes, now: float | None = None) -> None:
        """The goal's result is known: its `result_timeout` starts now."""
        entry = self._goals.get(key)
        if entry is not None and entry.ended_at is None:
            entry.ended_at = time.monotonic() if now is None else now

    def expire(self, now: float | None = None) -> list[bytes]:
        """Forget goals that ended more than `result_timeout` seconds ago; returns their keys."""
        now = time.monotonic() if now is None else now
        gone = [
            k
            for k, e in self._goals.items()
            if e.ended_at is not None and now - e.ended_at >= self.result_timeout
        ]
        for k in gone:
            del self._goals[k]
        return gone

    def next_expiry(self, now: float | None = None) -> float | None:
        """Seconds until the next finished goal expires (0 if one is due), or None when no
        goal has finished."""
        ended = [e.ended_at for e in self._goals.values() if e.ended_at is not None]
        if not ended:
            return None
        now = time.monotonic() if now is None else now
        return max(0.0, min(ended) + self.result_timeout - now)

    def status_array(self) -> _action_msgs_msg.GoalStatusArray:
        """action_msgs/GoalStatusArray of every goal still tracked, oldest first."""
        return GoalStatusArray(
            status_list=[GoalStatus(goal_info=e.info, status=e.state) for e in self._goals.values()]
        )

    def select_cancel(
        self, request: _action_msgs_srv.CancelGoal_Request
    ) -> tuple[int, list[_action_msgs_msg.GoalInfo]]:
        """rcl_action's reading of a CancelGoal request: (return code, GoalInfos to cancel).

        A zero goal id and zero stamp mean every goal; a zero id with a stamp, every goal
        accepted at or before it; an id, that goal (plus, with a stamp, the older ones).
        Only goals that may still take a cancel event are returned.
        """
        want = goal_key(request.goal_info.goal_id)
        stamp = request.goal_info.stamp
        stamp_ns = stamp.sec * 1_000_000_000 + stamp.nanosec
        candidates: list[GoalEntry] = []
        if any(want):
            target = self._goals.get(want)
            if target is None and stamp_ns == 0:
                return CancelGoal.Response.ERROR_UNKNOWN_GOAL_ID, []
            if target is not None:
                candidates.append(target)
        if stamp_ns or not any(want):
            candidates += [
                e
                for e in self._goals.values()
                if e not in candidates and (stamp_ns == 0 or e.stamp_ns <= stamp_ns)
            ]
        chosen = [e.info for e in candidates if is_cancelable(e.state)]
        if chosen:
            return CancelGoal.Response.ERROR_NONE, chosen
        if (
            any(want)
            and len(candidates) == 1
            and candidates[0].key == want
            and candidates[0].state in TERMINAL_STATES
        ):
            return CancelGoal.Response.ERROR_GOAL_TERMINATED, []
        return CancelGoal.Response.ERROR_REJECTED, []
