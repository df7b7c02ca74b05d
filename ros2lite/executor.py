"""A single-threaded executor: runs queued callbacks and due timers on the caller's thread.

Work items (anything with `execute()`) arrive on the context's queue. `spin_once` runs exactly
one callback, as rclpy promises; `spin` and `spin_until_future_complete` let a subscription
deliver a short batch per turn (bounded in count and time, and ended as soon as the awaited
future completes), which is what makes high message rates affordable in Python.
"""

from __future__ import annotations

import queue
import threading
import time
from collections.abc import Callable
from typing import Any

from ros2lite.context import Context, default_context

# at most this many samples of one subscription per turn in spin()/spin_until_future_complete
_BATCH = 512


class ExternalShutdownException(Exception):
    """Spinning ended because the process was asked to stop (SIGTERM), as in rclpy."""


class Future:
    """The result of an asynchronous operation (service call, goal), rclpy-style."""

    def __init__(self) -> None:
        # a plain flag for done(), which executors poll after every callback; the Event is
        # only for threads that block in wait()
        self._finished = False
        self._done = threading.Event()
        self._result: Any = None
        self._exception: BaseException | None = None
        self._callbacks: list[Callable[[Future], None]] = []
        self._cancelled = False

    def done(self) -> bool:
        return self._finished

    def cancelled(self) -> bool:
        return self._cancelled

    def cancel(self) -> None:
        if not self.done():
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
        self._finished = True
        self._done.set()
        for cb in self._callbacks:
            cb(self)

    def add_done_callback(self, cb: Callable[[Future], None]) -> None:
        if self.done():
            cb(self)
        else:
            self._callbacks.append(cb)

    def wait(self, timeout: float | None = None) -> bool:
        return self._done.wait(timeout)


class SingleThreadedExecutor:
    """Runs the work of its nodes: subscription samples, service requests, timers."""

    def __init__(self, *, context: Context | None = None) -> None:
        self.context = context or default_context()
        self._nodes: list[Any] = []

    def add_node(self, node: Any) -> bool:
        if node not in self._nodes:
            self._nodes.append(node)
            self.context.wake()
            return True
        return False

    def remove_node(self, node: Any) -> None:
        if node in self._nodes:
            self._nodes.remove(node)

    def get_nodes(self) -> list[Any]:
        return list(self._nodes)

    def _has_timers(self) -> bool:
        return any(node.timers for node in self._nodes)

    def _run_due_timers(self) -> tuple[bool, float | None]:
        """Fire due timers; return (whether any fired, seconds until the next one or None)."""
        fired = False
        wait: float | None = None
        for node in self._nodes:
            for timer in node.timers:
                remaining = timer.time_until_next_call()
                if remaining is None:
                    continue
                if remaining <= 0:
                    timer.execute()
                    fired = True
                    remaining = timer.time_until_next_call()
                    if remaining is None:
                        continue
                wait = remaining if wait is None else min(wait, remaining)
        return fired, wait

    def spin_once(self, timeout_sec: float | None = None) -> None:
        """Run due timers or one queued item, waiting up to `timeout_sec` (None: forever)."""
        self._check_terminating()
        self._spin_once(timeout_sec, None)
        self._check_terminating()

    def _check_terminating(self) -> None:
        if self.context.terminating:
            raise ExternalShutdownException()

    @staticmethod
    def _execute(item: Any, batch: bool, done: Callable[[], bool] | None) -> None:
        """Run one work item; in the run-until loops a subscription may deliver a batch."""
        if batch:
            many = getattr(item, 'execute_many', None)
            if many is not None:
                many(_BATCH, done)
                return
        item.execute()

    def _spin_once(self, timeout_sec: float | None,
                   done: Callable[[], bool] | None, batch: bool = False) -> None:
        # A bare wake-up (node or timer added, future finished elsewhere) is not work: keep
        # waiting for the rest of the timeout, unless `done()` holds or the context shut down.
        # Returning on every wake-up made `spin_once(node, timeout_sec=…)` loops busy-spin,
        # because each call adds the node to an executor, which queues a wake-up.
        work = self.context.work
        if not self._has_timers():
            # hot path: work already queued runs at once, with no deadline arithmetic
            try:
                item = work.get_nowait()
            except queue.Empty:
                item = None
            if item is not None:
                self._execute(item, batch, done)
                return
        if timeout_sec is None and not self._has_timers():
            # hot path (spin() and friends without timers): nothing to compute per item
            while True:
                item = work.get()
                if item is not None:
                    self._execute(item, batch, done)
                    return
                if not self.context.ok() or (done is not None and done()):
                    return
                if self._has_timers():
                    break  # a timer was added meanwhile: take the general path
        deadline = None if timeout_sec is None else time.monotonic() + timeout_sec
        while True:
            fired, next_timer = self._run_due_timers()
            if fired:
                return
            wait = None if deadline is None else max(0.0, deadline - time.monotonic())
            if next_timer is not None:
                wait = max(0.0, next_timer) if wait is None else min(wait, max(0.0, next_timer))
            try:
                item = work.get(timeout=wait) if wait != 0 else work.get_nowait()
            except queue.Empty:
                item = None
            if item is not None:
                self._execute(item, batch, done)
                return
            if not self.context.ok() or (done is not None and done()):
                return
            if deadline is not None and time.monotonic() >= deadline:
                return

    def spin(self) -> None:
        while self.context.ok():
            self._spin_once(None, None, True)
        self._check_terminating()

    def spin_until_future_complete(self, future: Future, timeout_sec: float | None = None
                                   ) -> None:
        future.add_done_callback(lambda _f: self.context.wake())
        deadline = None if timeout_sec is None else time.monotonic() + timeout_sec
        while self.context.ok() and not future.done():
            remaining = None if deadline is None else deadline - time.monotonic()
            if remaining is not None and remaining <= 0:
                return
            self._spin_once(remaining, future.done, True)
        if not future.done():
            self._check_terminating()

    def shutdown(self, timeout_sec: float | None = None) -> bool:
        self._nodes.clear()
        return True


def _executor_for(node: Any, executor: SingleThreadedExecutor | None) -> SingleThreadedExecutor:
    ex = executor or SingleThreadedExecutor(context=node.context)
    ex.add_node(node)
    return ex


def spin_once(node: Any, *, executor: SingleThreadedExecutor | None = None,
              timeout_sec: float | None = None) -> None:
    _executor_for(node, executor).spin_once(timeout_sec)


def spin(node: Any, executor: SingleThreadedExecutor | None = None) -> None:
    """Run the node's callbacks until shutdown (Ctrl-C raises KeyboardInterrupt, as rclpy)."""
    _executor_for(node, executor).spin()


def spin_until_future_complete(node: Any, future: Future,
                               executor: SingleThreadedExecutor | None = None,
                               timeout_sec: float | None = None) -> None:
    _executor_for(node, executor).spin_until_future_complete(future, timeout_sec)
