"""`fibonacci_action_server`: serves `fibonacci`, one feedback per second per goal.

Goals run in parallel (a reentrant group on a multi-threaded executor) and can be canceled,
as in the ROS demo.
"""

from __future__ import annotations

import time
from typing import TYPE_CHECKING

from ros2lite.action import ActionServer, CancelResponse, GoalResponse
from ros2lite.action.server import ServerGoalHandle
from ros2lite.bundled.runner import run_main
from ros2lite.callback_groups import ReentrantCallbackGroup
from ros2lite.msgs.action_tutorials_interfaces.action import (
    Fibonacci,
)
from ros2lite.node import Node

if TYPE_CHECKING:
    _Handle = ServerGoalHandle[Fibonacci.Goal, Fibonacci.Result, Fibonacci.Feedback]


class FibonacciActionServer(Node):
    """action_tutorials_py's server: Fibonacci sequences, one number a second."""

    def __init__(self) -> None:
        super().__init__('fibonacci_action_server')
        self._action_server = ActionServer(
            self,
            Fibonacci,
            'fibonacci',
            execute_callback=self.execute_callback,
            callback_group=ReentrantCallbackGroup(),
            goal_callback=self.goal_callback,
            cancel_callback=self.cancel_callback,
        )

    def destroy(self) -> None:
        """Withdraw the action server, then the node."""
        self._action_server.destroy()
        super().destroy_node()

    def goal_callback(self, goal_request: Fibonacci.Goal) -> GoalResponse:
        # this server takes several goals at once
        """Accept every goal."""
        self.get_logger().info('Received goal request')
        return GoalResponse.ACCEPT

    def cancel_callback(self, goal_handle: _Handle) -> CancelResponse:
        """Accept every cancel request."""
        self.get_logger().info('Received cancel request')
        return CancelResponse.ACCEPT

    async def execute_callback(self, goal_handle: _Handle) -> Fibonacci.Result:
        """Compute the sequence, publishing it as it grows; honour cancels."""
        self.get_logger().info('Executing goal...')
        feedback_msg = Fibonacci.Feedback()
        feedback_msg.partial_sequence = [0, 1]
        for i in range(1, goal_handle.request.order):
            if goal_handle.is_cancel_requested:
                goal_handle.canceled()
                self.get_logger().info('Goal canceled')
                return Fibonacci.Result()
            feedback_msg.partial_sequence.append(
                feedback_msg.partial_sequence[i] + feedback_msg.partial_sequence[i - 1]
            )
            self.get_logger().info(f'Publishing feedback: {feedback_msg.partial_sequence}')
            goal_handle.publish_feedback(feedback_msg)
            time.sleep(1)  # for demonstration, as the ROS demo does
        goal_handle.succeed()
        result = Fibonacci.Result()
        result.sequence = feedback_msg.partial_sequence
        self.get_logger().info(f'Returning result: {result.sequence}')
        return result


def main(args: list[str] | None = None) -> int:
    """`fibonacci_action_server`'s entry point."""
    import ros2lite
    from ros2lite.executors import MultiThreadedExecutor

    def body() -> None:
        # a multi-threaded executor, so goals are processed concurrently
        ros2lite.spin(FibonacciActionServer(), executor=MultiThreadedExecutor())

    return run_main(body, args)


if __name__ == '__main__':
    raise SystemExit(main())
