"""ActionServer and ActionClient in one process over a real router: accept, reject,
feedback, cancel, abort, results (also asked for before the goal ends), the latched status
topic and result retention."""

from __future__ import annotations

import threading
import time
from typing import Any

import pytest

from ros2lite.action import ActionClient, ActionServer, CancelResponse, GoalResponse
from ros2lite.action.server import ServerGoalHandle
from ros2lite.msgs.action_msgs.msg import GoalStatus
from ros2lite.msgs.action_msgs.srv import CancelGoal
from ros2lite.msgs.example_interfaces.action import Fibonacci
from ros2lite.node import Node
from ros2lite.qos import qos_profile_action_status_default
from tests.action.fixtures import Fixture
from tests.spinning import wait_until


def test_goal_feedback_and_result(fx: Fixture) -> None:
    fx.server()
    client = fx.client()
    feedback: list[Any] = []
    uuid = Fibonacci.Impl.SendGoalService.Request().goal_id
    uuid.uuid = list(range(16))
    handle = fx.wait(
        client.send_goal_async(Fibonacci.Goal(order=4), feedback.append, goal_uuid=uuid)
    )
    assert handle.accepted and bytes(handle.goal_id.uuid) == bytes(range(16))
    result_future = handle.get_result_async()  # asked before the goal ends
    wait_until(lambda: len(feedback) == 3)
    wait_until(lambda: handle.status == GoalStatus.STATUS_EXECUTING)
    assert not result_future.done()
    fx.release.set()
    response = fx.wait(result_future)
    assert response.status == GoalStatus.STATUS_SUCCEEDED
    assert list(response.result.sequence) == [0, 1, 1, 2, 3]
    assert [list(m.feedback.sequence) for m in feedback] == [
        [0, 1, 1],
        [0, 1, 1, 2],
        [0, 1, 1, 2, 3],
    ]
    assert all(bytes(m.goal_id.uuid) == bytes(range(16)) for m in feedback)
    wait_until(lambda: handle.status == GoalStatus.STATUS_SUCCEEDED)
    # the same result again, now answered at once
    assert fx.wait(handle.get_result_async()).status == GoalStatus.STATUS_SUCCEEDED


def test_rejected_goal(fx: Fixture) -> None:
    def goal_callback(goal: Any) -> GoalResponse:
        if goal.order == 7:
            raise ValueError('no sevens')  # answered as a rejection, the server lives on
        return GoalResponse.REJECT if goal.order > 5 else GoalResponse.ACCEPT

    fx.server(goal_callback=goal_callback)
    client = fx.client()
    for order in (6, 7):
        handle = fx.wait(client.send_goal_async(Fibonacci.Goal(order=order)))
        assert not handle.accepted and handle.status == GoalStatus.STATUS_UNKNOWN
    with pytest.raises(TypeError):
        handle.get_result_async()
    fx.release.set()
    assert client.send_goal(Fibonacci.Goal(order=7)) is None
    assert client.send_goal(Fibonacci.Goal(order=1)).status == GoalStatus.STATUS_SUCCEEDED


def test_cancel_accepted_and_rejected(fx: Fixture) -> None:
    fx.server(cancel_callback=lambda handle: CancelResponse.ACCEPT)
    client = fx.client()
    handle = fx.wait(client.send_goal_async(Fibonacci.Goal(order=2)))
    wait_until(lambda: handle.status == GoalStatus.STATUS_EXECUTING)
    response = fx.wait(handle.cancel_goal_async())
    assert response.return_code == CancelGoal.Response.ERROR_NONE
    assert [bytes(i.goal_id.uuid) for i in response.goals_canceling] == [bytes(handle.goal_id.uuid)]
    result = fx.wait(handle.get_result_async())
    assert result.status == GoalStatus.STATUS_CANCELED and list(result.result.sequence) == [-1]
    # canceling an ended goal
    again = fx.wait(handle.cancel_goal_async())
    assert again.return_code == CancelGoal.Response.ERROR_GOAL_TERMINATED


def test_default_cancel_callback_rejects(fx: Fixture) -> None:
    fx.server()
    client = fx.client()
    handle = fx.wait(client.send_goal_async(Fibonacci.Goal(order=2)))
    response = fx.wait(handle.cancel_goal_async())
    assert response.return_code == CancelGoal.Response.ERROR_REJECTED
    assert list(response.goals_canceling) == []
    fx.release.set()
    assert fx.wait(handle.get_result_async()).status == GoalStatus.STATUS_SUCCEEDED


def test_abort_and_failing_execute(fx: Fixture) -> None:
    def execute(goal_handle: ServerGoalHandle) -> Any:
        if goal_handle.request.order == 1:
            goal_handle.abort()
            return Fibonacci.Result(sequence=[7])
        if goal_handle.request.order == 2:
            raise RuntimeError('boom')
        return Fibonacci.Result()  # no terminal state set: aborted for the user

    fx.server(execute)
    client = fx.client()
    results = []
    for order in (1, 2, 3):
        handle = fx.wait(client.send_goal_async(Fibonacci.Goal(order=order)))
        results.append(fx.wait(handle.get_result_async()))
    assert [r.status for r in results] == [GoalStatus.STATUS_ABORTED] * 3
    assert [list(r.result.sequence) for r in results] == [[7], [], []]


def test_async_callbacks(fx: Fixture) -> None:
    async def execute(goal_handle: ServerGoalHandle) -> Any:
        goal_handle.publish_feedback(Fibonacci.Feedback(sequence=[1, 2]))
        goal_handle.succeed()
        return Fibonacci.Result(sequence=[goal_handle.request.order])

    async def goal_callback(goal: Any) -> GoalResponse:
        return GoalResponse.ACCEPT

    fx.server(execute, goal_callback=goal_callback)
    client = fx.client()
    feedback: list[Any] = []

    async def on_feedback(message: Any) -> None:
        feedback.append(list(message.feedback.sequence))

    handle = fx.wait(client.send_goal_async(Fibonacci.Goal(order=9), on_feedback))
    result = fx.wait(handle.get_result_async())
    assert result.status == GoalStatus.STATUS_SUCCEEDED and list(result.result.sequence) == [9]
    wait_until(lambda: feedback == [[1, 2]])


def test_late_status_subscriber_gets_the_latched_status(fx: Fixture) -> None:
    fx.release.set()
    fx.server()
    client = fx.client()
    handle = fx.wait(client.send_goal_async(Fibonacci.Goal(order=1)))
    fx.wait(handle.get_result_async())
    late = Node('late_status_listener', context=fx.context)
    got: list[Any] = []
    late.create_subscription(
        Fibonacci.Impl.GoalStatusMessage,
        '/fib/_action/status',
        got.append,
        qos_profile_action_status_default,
    )
    fx.executor.add_node(late)
    wait_until(lambda: got, timeout=15)
    [status] = got[-1].status_list
    assert bytes(status.goal_info.goal_id.uuid) == bytes(handle.goal_id.uuid)
    assert status.status == GoalStatus.STATUS_SUCCEEDED


def test_results_expire_after_result_timeout(fx: Fixture) -> None:
    fx.release.set()
    fx.server(result_timeout=0.3)
    client = fx.client()
    handle = fx.wait(client.send_goal_async(Fibonacci.Goal(order=1)))
    assert fx.wait(handle.get_result_async()).status == GoalStatus.STATUS_SUCCEEDED
    time.sleep(0.5)
    assert fx.wait(handle.get_result_async()).status == GoalStatus.STATUS_UNKNOWN


def test_blocking_send_goal(fx: Fixture) -> None:
    fx.release.set()
    fx.server()
    client = fx.client()
    response = client.send_goal(Fibonacci.Goal(order=3))
    assert response.status == GoalStatus.STATUS_SUCCEEDED
    assert list(response.result.sequence) == [0, 1, 1, 2]


def test_destroying_the_server_ends_execute_loops(fx: Fixture) -> None:
    ended = threading.Event()

    def execute(goal_handle: ServerGoalHandle) -> Any:
        while not goal_handle.is_cancel_requested:
            time.sleep(0.01)
        goal_handle.canceled()  # a no-op once the server is gone
        ended.set()
        return Fibonacci.Result()

    server = fx.server(execute)
    client = fx.client()
    handle = fx.wait(client.send_goal_async(Fibonacci.Goal(order=1)))
    wait_until(lambda: handle.status == GoalStatus.STATUS_EXECUTING)
    server.destroy()
    assert ended.wait(5)
    # gone from its node, with the event handlers of its publishers
    gone = (server, server._feedback_pub, server._status_pub)
    assert not [
        w for w in fx.server_node.waitables if w in gone or getattr(w, '_parent', 0) in gone
    ]


def test_finished_goals_expire_without_being_asked(fx: Fixture) -> None:
    """The server's timer forgets a finished goal `result_timeout` after it ended, even when
    nobody sends another request (rcl_action's timer)."""
    fx.release.set()
    server = fx.server(result_timeout=0.3)
    assert server.get_num_entities().num_timers == 1
    client = fx.client()
    handle = fx.wait(client.send_goal_async(Fibonacci.Goal(order=1)))
    fx.wait(handle.get_result_async())
    assert len(server._goal_handles) == 1
    wait_until(lambda: not server._goal_handles, timeout=10)


def test_deferred_goal_executes_after_the_node_left_the_executor(ros_context: Any) -> None:
    """`rclpy.spin_until_future_complete(node, …, executor)` removes the node again; a goal
    accepted then and executed later still runs on that executor (node.executor stays)."""
    import ros2lite
    from ros2lite.executors import SingleThreadedExecutor

    node = Node('deferring', context=ros_context)
    accepted: list[ServerGoalHandle] = []

    def execute(goal_handle: ServerGoalHandle) -> Any:
        goal_handle.succeed()
        return Fibonacci.Result(sequence=[7])

    ActionServer(node, Fibonacci, 'later', execute, handle_accepted_callback=accepted.append)
    client = ActionClient(node, Fibonacci, 'later')
    executor = SingleThreadedExecutor(context=ros_context)
    assert client.wait_for_server(timeout_sec=15)
    goal = client.send_goal_async(Fibonacci.Goal(order=1))
    ros2lite.spin_until_future_complete(node, goal, executor, timeout_sec=15)
    assert accepted and node.executor is executor
    accepted[0].execute()  # the node is in no executor now
    result = goal.result().get_result_async()
    ros2lite.spin_until_future_complete(node, result, executor, timeout_sec=15)
    assert list(result.result().result.sequence) == [7]
