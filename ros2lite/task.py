"""Futures and tasks, as rclpy has them: a Future is awaitable from a coroutine callback, and a
Task runs a coroutine step by step on an executor, resuming when the future it awaits is done.
"""

from __future__ import annotations

import inspect
import threading
from collections.abc import Callable, Generator
from typing import Any

__all__ = ['Future', 'Task']


class Future:
    """The result of an asynchronous operation (service call, goal, task).

    With an `executor`, done-callbacks run as tasks of that executor (as rclpy schedules
    them), on the thread spinning it; without one, on the thread that completes the future.
    """

    def __init__(self, *, executor: Any = None) -> None:
        # a plain flag for done(), which executors poll after every callback; the Event is
        # only made for threads that block in wait()
        self._finished = False
        self._lock = threading.Lock()
        self._event: threading.Event | None = None
        self._result: Any = None
        self._exception: BaseException | None = None
        # (callback, run on the completing thread rather than through the executor)
        self._callbacks: list[tuple[Callable[[Future], None], bool]] = []
        self._cancelled = False
        self._executor = executor

    def __await__(self) -> Generator[Future, None, Any]:
        # the task running the awaiting coroutine sees this future and resumes when it is done
        while not self._finished:
            yield self
        return self.result()

    def done(self) -> bool:
        return self._finished

    def cancelled(self) -> bool:
        return self._cancelled

    def cancel(self) -> None:
        """Give up on the result: the future is done, and cancelled."""
        if not self._finished:
            self._cancelled = True
            self._finish()

    def result(self) -> Any:
        if self._exception is not None:
            raise self._exception
        return self._result

    def exception(self) -> BaseException | None:
        return self._exception

    def set_result(self, result: Any) -> None:
        self._result = result
        self._finish()

    def set_exception(self, exc: BaseException) -> None:
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

    def _schedule(self, callback: Callable[[Future], None]) -> None:
        executor = self._executor
        if executor is not None:
            executor.create_task(callback, self)
        else:
            callback(self)

    def add_done_callback(self, callback: Callable[[Future], None]) -> None:
        """Call `callback(future)` once done (at once if it already is); through the
        future's executor when it has one."""
        with self._lock:
            if not self._finished:
                self._callbacks.append((callback, False))
                return
        self._schedule(callback)

    def _add_done_callback_now(self, callback: Callable[[Future], None]) -> None:
        """ros2lite's own bookkeeping (wake-ups, releasing a group): run on the completing
        thread, never as a task."""
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


class Task(Future):
    """Runs `handler(*args)`; if that is (or returns) a coroutine, one step per call.

    The executor calls the task; when the coroutine awaits a future that is not done, the
    task asks to be called again once it is (`reschedule`). Exceptions end the task and are
    kept as its exception."""

    def __init__(
        self,
        handler: Callable[..., Any],
        args: tuple[Any, ...] = (),
        kwargs: dict[str, Any] | None = None,
        *,
        executor: Any = None,
        reschedule: Callable[[Task], None] | None = None,
    ) -> None:
        super().__init__(executor=executor)
        self._handler: Callable[..., Any] | None = handler
        self._args = args
        self._kwargs = kwargs or {}
        self._coro: Any = None
        self._reschedule = reschedule
        # a step runs on one thread at a time; a call arriving meanwhile (the awaited future
        # completed on another thread before the step ended) is not lost: the running call
        # takes another step when it is done
        self._state = threading.Lock()
        self._executing = False
        self._again = False

    def executing(self) -> bool:
        return self._executing

    def __call__(self) -> None:
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
            awaited._add_done_callback_now(lambda _f: self._resume())
        else:
            self._resume()

    def _resume(self) -> None:
        if self._reschedule is not None and not self._finished:
            self._reschedule(self)

    def cancel(self) -> None:
        if self._coro is not None and not self._finished:
            self._coro.close()
        super().cancel()
