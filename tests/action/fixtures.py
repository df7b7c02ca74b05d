"""A server node and a client node on a multi-threaded executor, shared by the action tests
(the `fx` fixture, re-exported by conftest)."""

from __future__ import annotations

import threading
import time
from collections.abc import Iterator
from typing import Any

import pytest

from ros2lite.action import ActionClient, ActionServer
from ros2lite.action.server import ServerGoalHandle
from ros2lite.callback_groups import ReentrantCallbackGroup
from ros2lite.executors import MultiThreadedExecutor
from ros2lite.msgs.example_interfaces.action import Fibonacci  # type: ignore[attr-defined]
from ros2lite.node import Node
from tests.spinning import wait_until


class Fixture:
    """A server node and a client node spun by a multi-threaded executor in a thread."""

    def __init__(self, context: Any) -> None:
        self.context = context
        self.server_node = Node('fib_server', context=context)
        self.client_node = Node('fib_client', context=context)
        self.executor = MultiThreadedExecutor(context=context)
        self.executor.add_node(self.server_node)
        self.executor.add_node(self.client_node)
        self.thread = threading.Thread(target=self.executor.spin, daemon=True)
        self.events: list[str] = []
        self.release = threading.Event()

    def server(self, execute: Any = None, **kwargs: Any) -> ActionServer:
        return ActionServer(
            self.server_node,
            Fibonacci,
            'fib',
            execute or self.execute,
            callback_group=ReentrantCallbackGroup(),
            **kwargs,
        )

    def client(self) -> ActionClient:
        client = ActionClient(self.client_node, Fibonacci, 'fib')
        assert client.wait_for_server(timeout_sec=15)
        return client

    def execute(self, goal_handle: ServerGoalHandle) -> Any:
        """Fibonacci with feedback; waits for `release` before the last step, and stops
        early when a cancel was accepted."""
        seq = [0, 1]
        for i in range(1, goal_handle.request.order):
            seq.append(seq[i] + seq[i - 1])
            goal_handle.publish_feedback(Fibonacci.Feedback(sequence=seq))
        deadline = time.monotonic() + 15
        while not self.release.is_set() and time.monotonic() < deadline:
            if goal_handle.is_cancel_requested:
                goal_handle.canceled()
                return Fibonacci.Result(sequence=[-1])
            time.sleep(0.01)
        goal_handle.succeed()
        return Fibonacci.Result(sequence=seq)

    def wait(self, future: Any, timeout: float = 15) -> Any:
        wait_until(future.done, timeout=timeout)
        return future.result()


@pytest.fixture
def fx(ros_context: Any) -> Iterator[Fixture]:
    f = Fixture(ros_context)
    f.thread.start()
    try:
        yield f
    finally:
        f.release.set()
        f.executor.shutdown()
        ros_context.try_shutdown()
        f.thread.join(timeout=5)
