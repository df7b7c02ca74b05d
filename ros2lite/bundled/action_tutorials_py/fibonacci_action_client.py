"""`fibonacci_action_client`: sends `fibonacci` one goal of order 10, logs the feedback and
the result, then exits."""

from __future__ import annotations

from typing import TYPE_CHECKING

import ros2lite
from ros2lite.action import ActionClient
from ros2lite.bundled.runner import run_node
from ros2lite.msgs.action_msgs.msg import GoalStatus
from ros2lite.msgs.action_tutorials_interfaces.action import (
    Fibonacci,
)
from ros2lite.node import Node

if TYPE_CHECKING:
    from ros2lite.action import ClientGoalHandle
    from ros2lite.task import Future
    from ros2lite.type_support import FeedbackMessage, GetResultResponse

    _Handle = ClientGoalHandle[Fibonacci.Goal, Fibonacci.Result, Fibonacci.Feedback]


class FibonacciActionClient(Node):
    """action_tutorials_py's client: one goal, its feedback and result logged."""

    def __init__(self) -> None:
        super().__init__('fibonacci_action_client')
        self._action_client = ActionClient(self, Fibonacci, 'fibonacci')

    def goal_response_callback(self, future: Future[_Handle]) -> None:
        """The server answered: ask for the result of an accepted goal."""
        goal_handle = future.result()
        if goal_handle is None or not goal_handle.accepted:
            self.get_logger().info('Goal rejected :(')
            return
        self.get_logger().info('Goal accepted :)')
        self._get_result_future = goal_handle.get_result_async()
        self._get_result_future.add_done_callback(self.get_result_callback)

    def feedback_callback(self, feedback: FeedbackMessage[Fibonacci.Feedback]) -> None:
        """Log each partial sequence."""
        self.get_logger().info(f'Received feedback: {feedback.feedback.partial_sequence}')

    def get_result_callback(self, future: Future[GetResultResponse[Fibonacci.Result]]) -> None:
        """Log the result, then leave."""
        response = future.result()
        assert response is not None  # the client never cancels this future
        result = response.result
        status = response.status
        if status == GoalStatus.STATUS_SUCCEEDED:
            self.get_logger().info(f'Goal succeeded! Result: {result.sequence}')
        else:
            self.get_logger().info(f'Goal failed with status: {status}')
        ros2lite.shutdown(context=self.context)  # leave after the result, as the demo does

    def send_goal(self) -> None:
        """Wait for the server and send a goal of order 10."""
        self.get_logger().info('Waiting for action server...')
        self._action_client.wait_for_server()
        goal_msg = Fibonacci.Goal()
        goal_msg.order = 10
        self.get_logger().info('Sending goal request...')
        self._send_goal_future = self._action_client.send_goal_async(
            goal_msg, feedback_callback=self.feedback_callback
        )
        self._send_goal_future.add_done_callback(self.goal_response_callback)


def _make() -> FibonacciActionClient:
    client = FibonacciActionClient()
    client.send_goal()
    return client


def main(args: list[str] | None = None) -> int:
    """`fibonacci_action_client`'s entry point."""
    return run_node(_make, args)


if __name__ == '__main__':
    raise SystemExit(main())
