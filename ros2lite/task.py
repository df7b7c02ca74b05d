"""Futures and tasks, as rclpy has them: a Future is awaitable from a coroutine callback, and a
Task runs a coroutine step by step on an executor, resuming when the future it awaits is done.
"""

from __future__ import annotations

import inspect
import threading
from collections.abc import Callable, Coroutine, Generator
from typing import Any, Generic, Protocol, TypeVar, final

__all__ = ['Future', 'Task', 'TaskRunner']

T = TypeVar('T')


class TaskRunner(Protocol):
    """What a future needs of its executor (:class:`ros2lite.executors.Executor` is one): a
    way to run its done-callbacks as tasks, named here so futures sit below executors."""

    def create_task(
        self,
        callback: Callable[..., object] | Coroutine[object, object, object],
        *args: object,
        **kwargs: object,
    ) -> Task:
        """Run `callback(*args, **kwargs)` as a Task of this executor."""
        ...


class Future(Generic[T]):
    """The result of an asynchronous operation (service call, goal, task).

    With an `executor`, done-callbacks run as tasks of that executor (as rclpy schedules
    them), on the thread spinning it; without one, on the thread that completes the future.
    """

    def __init__(self, *, executor: TaskRunner | None = None) -> None:
        # a plain flag for done(), which executors poll after every callback; the Event is
        # only made for threads that block in wait()
        self._finished = False
        self._lock = threading.Lock()
        self._event: threading.Event | None = None
        self._result: T | None = None
        self._exception: BaseException | None = None
        # (callback, run on the completing thread rather than through the executor)
        self._callbacks: list[tuple[Callable[[Future[T]], object], bool]] = []
        self._cancelled = False
        self._executor = executor

    def __await__(self) -> Generator[Future[T], None, T | None]:
        # the task running the awaiting coroutine sees this future and resumes when it is done
        while not self._finished:
            yield self
        return self.result()

    def done(self) -> bool:
        """Whether a result, an exception or a cancellation has ended it."""
        return self._finished

    def cancelled(self) -> bool:
        """Whether it ended by `cancel()`."""
        return self._cancelled

    def cancel(self) -> None:
        """Give up on the result: the future is done, and cancelled."""
        if not self._finished:
            self._cancelled = True
            self._finish()

    def result(self) -> T | None:
        """The result (None while pending or once cancelled); raises its exception."""
        if self._exception is not None:
            raise self._exception
        return self._result

    def exception(self) -> BaseException | None:
        """The exception it ended with, if any."""
        return self._exception

    def set_result(self, result: T) -> None:
        """Complete it with `result` (done callbacks run now, on this thread)."""
        self._result = result
        self._finish()

    def set_exception(self, exc: BaseException) -> None:
        """Complete it with an exception that `result()` raises."""
        self._exception = exc
        self._finish()

    def _finish(self) -> None:
        with self._lock:
            if self._finished:
                return
            self._finished = True
            event, callbacks, self._callbacks = self._event, self._callbacks, []
        if event is not None:
            event.set()
        for cb, now in callbacks:
            if now:
                cb(self)
            else:
                self._schedule(cb)

    def _schedule(self, callback: Callable[[Future[T]], object]) -> None:
        executor = self._executor
        if executor is not None:
            executor.create_task(callback, self)
        else:
            callback(self)

    def add_done_callback(self, callback: Callable[[Future[T]], object]) -> None:
        """Call `callback(future)` once done (at once if it already is); through the
        future's executor when it has one."""
        with self._lock:
            if not self._finished:
                self._callbacks.append((callback, False))
                return
        self._schedule(callback)

    def add_done_callback_now(self, callback: Callable[[Future[T]], object]) -> None:
        """`callback(self)` on the completing thread, never as a task: for bookkeeping that
        must not wait for an executor (wake-ups, releasing a group, answering a request)."""
        with self._lock:
            if not self._finished:
                self._callbacks.append((callback, True))
                return
        callback(self)

    def wait(self, timeout: float | None = None) -> bool:
        """Block this thread until done; True unless the timeout passed first."""
        with self._lock:
            if self._finished:
                return True
            if self._event is None:
                self._event = threading.Event()
            event = self._event
        return event.wait(timeout)


@final  # executors tell tasks from entities by `type(item) is Task`
class Task(Future[Any]):
    """Runs `handler(*args)`; if that is (or returns) a coroutine, one step per call.

    The executor calls the task; when the coroutine awaits a future that is not done, the
    task asks to be called again once it is (`reschedule`). Exceptions end the task and are
    kept as its exception."""

    def __init__(
        self,
        handler: Callable[..., object],
        args: tuple[object, ...] = (),
        kwargs: dict[str, object] | None = None,
        *,
        executor: TaskRunner | None = None,
        reschedule: Callable[[Task], None] | None = None,
    ) -> None:
        super().__init__(executor=executor)
        self._handler: Callable[..., object] | None = handler
        self._args = args
        self._kwargs = kwargs or {}
        self._coro: Coroutine[object, None, object] | None = None
        self._reschedule = reschedule
        # a step runs on one thread at a time; a call arriving meanwhile (the awaited future
        # completed on another thread before the step ended) is not lost: the running call
        # takes another step when it is done
        self._state = threading.Lock()
        self._executing = False
        self._again = False

    def executing(self) -> bool:
        """Whether a step of it runs right now (on some thread)."""
        return self._executing

    def __call__(self) -> None:
        """Take the next step (the executor calls this; a concurrent call is not lost)."""
        with self._state:
            if self._finished:
                return
            if self._executing:
                self._again = True
                return
            self._executing = True
        try:
            while True:
                self._step()
                with self._state:
                    if not self._again or self._finished:
                        return
                    self._again = False
        finally:
            with self._state:
                self._executing = False

    def _step(self) -> None:
        if self._coro is None:
            handler, self._handler = self._handler, None
            if handler is None:
                return
            try:
                value = handler(*self._args, **self._kwargs)
            except Exception as e:
                self.set_exception(e)
                return
            if not inspect.iscoroutine(value):
                self.set_result(value)
                return
            self._coro = value
        try:
            awaited = self._coro.send(None)
        except StopIteration as stop:
            self.set_result(stop.value)
            return
        except Exception as e:
            self.set_exception(e)
            return
        if self._reschedule is None:
            return
        if isinstance(awaited, Future) and not awaited.done():
            awaited.add_done_callback_now(lambda _f: self._resume())
        else:
            self._resume()

    def _resume(self) -> None:
        if self._reschedule is not None and not self._finished:
            self._reschedule(self)

    def cancel(self) -> None:
        """Close the coroutine (if started) and cancel the task."""
        if self._coro is not None and not self._finished:
            self._coro.close()
        super().cancel()
