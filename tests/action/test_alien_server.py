"""ros2lite's ActionClient against the alien (bare zenoh) server: feedback, status from the
transient-local status topic, a result asked for while the goal runs, and cancel."""

from __future__ import annotations

from typing import Any

from ros2lite.action import ActionClient
from ros2lite.executors import SingleThreadedExecutor
from ros2lite.msgs.action_msgs.msg import GoalStatus
from ros2lite.msgs.example_interfaces.action import Fibonacci
from ros2lite.node import Node
from tests.action.alien import AlienFibonacciServer
from tests.spinning import spin_until


def test_client_against_alien_server(ros_context: Any, alien_server: AlienFibonacciServer) -> None:
    node = Node('client_of_alien', context=ros_context)
    client = ActionClient(node, Fibonacci, 'alien_fib')
    assert client.wait_for_server(timeout_sec=15)
    ex = SingleThreadedExecutor(context=ros_context)
    ex.add_node(node)
    feedback: list[Any] = []
    goal_future = client.send_goal_async(Fibonacci.Goal(order=4), feedback.append)
    spin_until(ex, goal_future.done, timeout=15)
    handle = goal_future.result()
    assert handle.accepted
    result_future = handle.get_result_async()
    spin_until(ex, result_future.done, timeout=15)
    result = result_future.result()
    assert result.status == GoalStatus.STATUS_SUCCEEDED
    assert list(result.result.sequence) == [0, 1, 1, 2, 3]
    spin_until(ex, lambda: len(feedback) == 3, timeout=5)
    assert [list(m.feedback.sequence) for m in feedback][-1] == [0, 1, 1, 2, 3]
    assert {bytes(m.goal_id.uuid) for m in feedback} == {bytes(handle.goal_id.uuid)}

    long_future = client.send_goal_async(Fibonacci.Goal(order=1000))
    spin_until(ex, long_future.done, timeout=15)
    long_goal = long_future.result()
    spin_until(ex, lambda: long_goal.status == GoalStatus.STATUS_EXECUTING, timeout=15)
    cancel_future = long_goal.cancel_goal_async()
    spin_until(ex, cancel_future.done, timeout=15)
    assert [bytes(g.goal_id.uuid) for g in cancel_future.result().goals_canceling] == [
        bytes(long_goal.goal_id.uuid)
    ]
    result_future = long_goal.get_result_async()
    spin_until(ex, result_future.done, timeout=15)
    assert result_future.result().status == GoalStatus.STATUS_CANCELED
    spin_until(ex, lambda: long_goal.status == GoalStatus.STATUS_CANCELED, timeout=5)
