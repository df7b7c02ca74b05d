"""Waitables of one's own: `notify_ready()` from any thread makes the node's executor take the
data and run `execute` (a coroutine too) in the waitable's group."""

from __future__ import annotations

import threading
from typing import Any

from ros2lite.callback_groups import ReentrantCallbackGroup
from ros2lite.executors import SingleThreadedExecutor
from ros2lite.node import Node
from ros2lite.waitable import NumberOfEntities, Waitable
from tests.spinning import spin_until


class Counter(Waitable):
    def __init__(self) -> None:
        super().__init__(ReentrantCallbackGroup())
        self.pending = 0
        self.seen: list[tuple[int, str]] = []

    def take_data(self) -> int:
        taken, self.pending = self.pending, 0
        return taken

    async def execute(self, taken_data: int) -> None:
        self.seen.append((taken_data, threading.current_thread().name))


def test_notify_ready_runs_execute_on_the_executor(ros_context: Any) -> None:
    node = Node('waiting', context=ros_context)
    waitable = Counter()
    node.add_waitable(waitable)
    executor = SingleThreadedExecutor(context=ros_context)
    executor.add_node(node)
    executor.spin_once(timeout_sec=0.05)
    assert waitable.seen == []  # nothing to do until told

    def produce() -> None:
        waitable.pending = 3
        waitable.notify_ready()

    threading.Thread(target=produce).start()
    spin_until(executor, lambda: waitable.seen)
    assert waitable.seen == [(3, threading.current_thread().name)]
    waitable.destroy()
    assert waitable not in node.waitables


def test_number_of_entities_adds_up() -> None:
    total = NumberOfEntities(1, 2, 3, 4, 5, 6)
    total += NumberOfEntities(10, 20, 30, 40, 50, 60)
    assert total == NumberOfEntities(11, 22, 33, 44, 55, 66)
