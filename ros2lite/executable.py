"""What subscriptions, services, clients, timers and guard conditions share: they belong to a
node and a callback group, and when work arrives (on any thread) they wake the executor their
node was added to, at most once until it has run them.
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from typing import TYPE_CHECKING, Any, Protocol

from ros2lite.callback_groups import CallbackGroup

if TYPE_CHECKING:
    from ros2lite.executors import Executor
    from ros2lite.node import Node
    from ros2lite.task import Task

__all__ = ['Destroyable', 'Executable', 'GuardCondition', 'current_execution']


class _Running(threading.local):
    """What this thread is executing (class defaults: nothing, read without getattr)."""

    executor: Executor | None = None
    entity: Executable | None = None


# which executor and entity the current thread runs a callback for (set by the executor):
# coroutine callbacks continue on it, and blocking calls check it for deadlocks
_running = _Running()


class Destroyable(Protocol):
    """Anything a node tears down when it is destroyed."""

    def destroy(self) -> None:
        """Release what it holds (entities leave the graph)."""
        ...


def current_execution() -> tuple[Executor | None, Executable | None]:
    """(executor, entity) whose callback this thread is running, or (None, None)."""
    return _running.executor, _running.entity


class Executable:
    """Base of everything an executor runs for a node."""

    # completing a client's future runs no user callback of its own, so it need not wait for
    # its group: a coroutine holding the group while it awaits that very future would
    # otherwise never resume
    needs_group = True
    is_timer = False
    # the entity calls _notify() whenever it gets work, also while its node has no executor
    # (so add_node need not ask it); user waitables that only answer is_ready() do not
    notifies_itself = False

    def __init__(self, node: Node | None, callback_group: CallbackGroup | None) -> None:
        from ros2lite.callback_groups import MutuallyExclusiveCallbackGroup

        self._node = node
        self.callback_group = callback_group or (
            node.default_callback_group if node is not None else MutuallyExclusiveCallbackGroup()
        )
        self.callback_group.add_entity(self)
        # in the executor's queue, or running: set and cleared by the owner of the queue
        self._scheduled = False

    def _notify(self) -> None:
        """Any thread: work arrived; queue this entity on its node's executor (once)."""
        if self._scheduled:
            return
        # only entities of a node queue work (a nodeless timer is never notified)
        node: Node = self._node  # type: ignore[assignment]
        executor = node._executor
        if executor is None:
            # no executor: the next add_node must look (and, should one be added right now,
            # the second look below queues the work itself, so it is never lost)
            node._unqueued_work = True
            executor = node._executor
            if executor is None:
                return
        self._scheduled = True
        executor._enqueue(self)

    def _executed(self) -> None:
        """Executor thread, after `_execute`: clear the flag *before* looking for more work,
        so work that arrives meanwhile is either seen here or queued by `_notify`."""
        self._scheduled = False
        if self._has_work():
            self._notify()

    def _has_work(self) -> bool:
        return False

    def _call(
        self,
        callback: Callable[..., object],
        *args: object,
        then: Callable[[Any], None] | None = None,  # gets what the user's callback returned
    ) -> Task | None:
        """Run a user callback on the executor's terms (a coroutine becomes a Task). That is
        the executor running this entity now: a multi-threaded one may run it after the node
        has moved on (spin_once's helper removes the node once the work is handed over)."""
        executor = _running.executor
        if executor is None and self._node is not None:
            executor = self._node._executor
        if executor is not None:
            return executor._run_callback(callback, *args, then=then)
        result = callback(*args)
        if then is not None:
            then(result)
        return None

    def _execute(self, batch: bool, stop: Callable[[], bool] | None) -> Task | None:
        """Run pending work; return a Task if a coroutine callback is still running (it
        keeps the callback group until it finishes)."""
        raise NotImplementedError


class GuardCondition(Executable):
    """`trigger()` from any thread makes the executor call `callback()` on its thread."""

    def __init__(
        self,
        node: Node | None,
        callback: Callable[[], object] | None,
        callback_group: CallbackGroup | None = None,
    ) -> None:
        super().__init__(node, callback_group)
        self.callback = callback
        self._triggered = False

    def trigger(self) -> None:
        """Any thread: have the executor run the callback (once per trigger burst)."""
        self._triggered = True
        self._notify()

    def _has_work(self) -> bool:
        return self._triggered

    def _execute(self, batch: bool, stop: Callable[[], bool] | None) -> Task | None:
        self._triggered = False
        return self._call(self.callback) if self.callback is not None else None

    def destroy(self) -> None:
        """Never run the callback again."""
        self.callback = None
