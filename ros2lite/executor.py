"""A single-threaded executor: runs queued callbacks and due timers on the caller's thread."""

from __future__ import annotations

import queue
import threading
import time
from collections.abc import Callable
from typing import Any

from ros2lite.context import Context, default_context


class Future:
    """The result of an asynchronous operation (service call, goal), rclpy-style."""

    def __init__(self) -> None:
        self._done = threading.Event()
        self._result: Any = None
        self._exception: BaseException | None = None
        self._callbacks: list[Callable[[Future], None]] = []
        self._cancelled = False

    def done(self) -> bool:
        return self._done.is_set()

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

    def _timers(self) -> list[Any]:
        return [t for n in self._nodes for t in n.timers if not t.is_canceled()]

    def _run_due_timers(self) -> float | None:
        """Fire due timers; return seconds until the next one (None if there is none)."""
        wait: float | None = None
        for timer in self._timers():
            remaining = timer.time_until_next_call()
            if remaining is None:
                continue
            if remaining <= 0:
                timer.execute()
                remaining = timer.time_until_next_call()
                if remaining is None:
                    continue
            wait = remaining if wait is None else min(wait, remaining)
        return wait

    def spin_once(self, timeout_sec: float | None = None) -> None:
        """Do at most one queued item (plus any due timers), waiting up to `timeout_sec`."""
        next_timer = self._run_due_timers()
        wait = timeout_sec
        if next_timer is not None:
            wait = max(0.0, next_timer) if wait is None else min(wait, max(0.0, next_timer))
        try:
            item = self.context.work.get(timeout=wait) if wait != 0 else \
                self.context.work.get_nowait()
        except queue.Empty:
            item = None
        if item is not None:
            item.execute()
        self._run_due_timers()

    def spin(self) -> None:
        while self.context.ok():
            self.spin_once(None)

    def spin_until_future_complete(self, future: Future, timeout_sec: float | None = None
                                   ) -> None:
        future.add_done_callback(lambda _f: self.context.wake())
        deadline = None if timeout_sec is None else time.monotonic() + timeout_sec
        while self.context.ok() and not future.done():
            remaining = None if deadline is None else deadline - time.monotonic()
            if remaining is not None and remaining <= 0:
                return
            self.spin_once(remaining)

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
