"""The goal rules the server applies: rcl_action's transitions, cancel selection, status
array and result expiry."""

from __future__ import annotations

from typing import Any

import pytest

from ros2lite.action.goals import (
    CancelGoal,
    GoalEvent,
    GoalInfo,
    GoalStatus,
    GoalTable,
    InvalidGoalTransition,
    action_type_name,
    goal_id_hex,
    goal_key,
    new_goal_id,
    next_state,
    status_name,
)
from ros2lite.interfaces import get_interface

Time = get_interface('builtin_interfaces/msg/Time')
S = GoalStatus


def info(n: int, sec: int) -> Any:
    return GoalInfo(
        goal_id=get_interface('unique_identifier_msgs/msg/UUID')(uuid=[n] * 16), stamp=Time(sec=sec)
    )


def cancel(n: int = 0, sec: int = 0) -> Any:
    return CancelGoal.Request(goal_info=info(n, sec))


def test_transitions_follow_rcl_action() -> None:
    assert next_state(S.STATUS_ACCEPTED, GoalEvent.EXECUTE) == S.STATUS_EXECUTING
    assert next_state(S.STATUS_ACCEPTED, GoalEvent.CANCEL_GOAL) == S.STATUS_CANCELING
    assert next_state(S.STATUS_EXECUTING, GoalEvent.SUCCEED) == S.STATUS_SUCCEEDED
    assert next_state(S.STATUS_EXECUTING, GoalEvent.ABORT) == S.STATUS_ABORTED
    assert next_state(S.STATUS_CANCELING, GoalEvent.CANCELED) == S.STATUS_CANCELED
    assert next_state(S.STATUS_CANCELING, GoalEvent.SUCCEED) == S.STATUS_SUCCEEDED
    for state, event in [
        (S.STATUS_ACCEPTED, GoalEvent.SUCCEED),
        (S.STATUS_EXECUTING, GoalEvent.CANCELED),
        (S.STATUS_SUCCEEDED, GoalEvent.ABORT),
        (S.STATUS_CANCELING, GoalEvent.CANCEL_GOAL),
    ]:
        with pytest.raises(InvalidGoalTransition, match=status_name(state)):
            next_state(state, event)
    assert isinstance(InvalidGoalTransition('x'), RuntimeError)


def test_status_names_and_ids() -> None:
    assert [status_name(s) for s in range(8)] == [
        'UNKNOWN',
        'ACCEPTED',
        'EXECUTING',
        'CANCELING',
        'SUCCEEDED',
        'CANCELED',
        'ABORTED',
        'UNKNOWN',
    ]
    a, b = new_goal_id(), new_goal_id()
    assert len(goal_key(a)) == 16 and goal_key(a) != goal_key(b)
    assert goal_key(a)[6] >> 4 == 4  # a version 4 UUID, as rclpy makes them
    assert goal_id_hex(a) == bytes(a.uuid).hex() and len(goal_id_hex(a)) == 32
    assert action_type_name('pkg/Fib') == 'pkg/action/Fib'
    with pytest.raises(ValueError):
        action_type_name('pkg/msg/Fib')


def test_status_array_and_expiry() -> None:
    table = GoalTable(result_timeout=10)
    for n in (1, 2, 3):
        table.add(info(n, n))
    with pytest.raises(RuntimeError):
        table.add(info(1, 9))
    table.update(bytes([1] * 16), GoalEvent.EXECUTE)
    assert table.update(bytes([1] * 16), GoalEvent.SUCCEED) == S.STATUS_SUCCEEDED
    array = table.status_array()
    assert [(s.goal_info.goal_id.uuid[0], s.status) for s in array.status_list] == [
        (1, S.STATUS_SUCCEEDED),
        (2, S.STATUS_ACCEPTED),
        (3, S.STATUS_ACCEPTED),
    ]
    ended = table.get(bytes([1] * 16))
    assert ended is not None and ended.ended_at is None
    assert table.expire(1e12) == []  # kept until its result is known
    table.finish(bytes([1] * 16))
    assert ended.ended_at is not None
    assert table.expire(ended.ended_at + 9.9) == []
    assert table.expire(ended.ended_at + 10) == [bytes([1] * 16)]
    assert len(table) == 2


def test_cancel_selection() -> None:
    table = GoalTable(result_timeout=10)
    for n in (1, 2, 3):
        table.add(info(n, n * 10))
    table.update(bytes([3] * 16), GoalEvent.EXECUTE)
    table.update(bytes([3] * 16), GoalEvent.ABORT)

    def ids(code_and_infos: tuple[int, list[Any]]) -> tuple[int, list[int]]:
        code, infos = code_and_infos
        return code, [i.goal_id.uuid[0] for i in infos]

    R = CancelGoal.Response
    assert ids(table.select_cancel(cancel())) == (R.ERROR_NONE, [1, 2])  # all active
    assert ids(table.select_cancel(cancel(2))) == (R.ERROR_NONE, [2])  # one goal
    assert ids(table.select_cancel(cancel(0, 10))) == (R.ERROR_NONE, [1])  # up to a stamp
    assert ids(table.select_cancel(cancel(2, 10))) == (R.ERROR_NONE, [2, 1])  # both rules
    assert ids(table.select_cancel(cancel(9))) == (R.ERROR_UNKNOWN_GOAL_ID, [])
    assert ids(table.select_cancel(cancel(3))) == (R.ERROR_GOAL_TERMINATED, [])
    table.update(bytes([1] * 16), GoalEvent.CANCEL_GOAL)
    table.update(bytes([2] * 16), GoalEvent.CANCEL_GOAL)
    assert ids(table.select_cancel(cancel())) == (R.ERROR_REJECTED, [])
