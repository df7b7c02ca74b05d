"""Tasks step coroutines on request and resume when the future they await is done."""

from __future__ import annotations

from typing import Any

import pytest

from ros2lite.task import Future, Task


def test_plain_callable_task_finishes_in_one_step() -> None:
    task = Task(lambda a, b: a + b, (2, 3))
    assert not task.done()
    task()
    assert task.done() and task.result() == 5


def test_coroutine_task_is_rescheduled_when_its_future_completes() -> None:
    gate = Future()
    queued: list[Task] = []

    async def work() -> str:
        value = await gate
        return f'got {value}'

    task = Task(work, reschedule=queued.append)
    task()
    assert not task.done() and task.executing() is False and queued == []
    gate.set_result(7)
    assert queued == [task]
    queued.pop()()
    assert task.result() == 'got 7'


def test_exceptions_end_the_task() -> None:
    async def broken() -> None:
        raise KeyError('x')

    task = Task(broken)
    task()
    assert task.done() and isinstance(task.exception(), KeyError)
    with pytest.raises(KeyError):
        task.result()


def test_a_call_while_a_step_runs_is_not_lost() -> None:
    """The awaited future may complete (and the task be called again, by another executor
    thread) while the step that awaits it has not returned yet; that call must not be lost."""
    queued: list[Task] = []

    class CompletesWhileRegistering(Future):
        def add_done_callback_now(self, callback: Any) -> None:
            super().add_done_callback_now(callback)
            self.set_result(5)  # runs the callback: the task is re-queued…
            queued.pop()()  # …and called at once, while its step is still running

    async def work() -> int:
        return int(await CompletesWhileRegistering())

    task = Task(work, reschedule=queued.append)
    task()
    assert task.done() and task.result() == 5


def test_a_future_with_an_executor_schedules_its_callbacks() -> None:
    """Done-callbacks of a Future(executor=…) become tasks of that executor, as rclpy's."""

    class Recorder:
        def __init__(self) -> None:
            self.tasks: list[tuple[Any, tuple[Any, ...]]] = []

        def create_task(self, callback: Any, *args: Any) -> None:
            self.tasks.append((callback, args))

    executor = Recorder()
    future = Future(executor=executor)
    ran: list[Any] = []
    future.add_done_callback(ran.append)
    future.set_result(1)
    assert ran == [] and executor.tasks == [(ran.append, (future,))]
    future.add_done_callback(ran.append)  # already done: scheduled too
    assert len(executor.tasks) == 2 and ran == []
    plain = Future()
    plain.add_done_callback(ran.append)
    plain.set_result(2)
    assert ran == [plain]  # without an executor: at once, on the completing thread
