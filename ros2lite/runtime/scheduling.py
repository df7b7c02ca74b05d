"""Who runs a node's work, and when: :class:`NodeWork`, the one owner of a node's executor
and of its entities' "queued" flags.

A sample arriving on a Zenoh thread, a node moving between executors (`spin_once(node)` adds
and removes it per call), a multi-threaded worker finishing a callback and an executor being
shut down all meet here, so their order is decided in one place: an entity is queued at most
once until it has run, work that arrives while the node has no executor is held until
`attach`, and an entry left in a former executor's queue is dropped, not run twice.

Where an idle executor waits (a node's kept channels) is ros2lite.runtime.parking's room.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any, Generic, Protocol, TypeVar

__all__ = ['NodeWork', 'Scheduled', 'WorkExecutor']


class Scheduled:
    """Base of what a NodeWork queues (every Executable). Its flag says "in an executor's
    queue, or running"; only this module sets it."""

    _scheduled = False
    # the entity tells its NodeWork whenever it gets work, also while its node has no
    # executor (so attach need not ask it); user waitables that only answer is_ready() do not
    notifies_itself = False
    # going away (set before its channel closes): its node keeps no channel for it (parking)
    destroyed = False

    @property
    def scheduled(self) -> bool:
        """Queued on an executor or running now (read-only: NodeWork decides)."""
        return self._scheduled

    def has_work(self) -> bool:
        """Whether running it now would find something to do."""
        return False


class WorkExecutor(Protocol):
    """An executor as a NodeWork sees it."""

    def wake(self) -> None:
        """Any thread: make a waiting spin look again."""
        ...


ExecutorT = TypeVar('ExecutorT', bound=WorkExecutor)


class NodeWork(Generic[ExecutorT]):
    """The scheduling state of one node: the executor it is attached to (and the one before,
    whose queue may still hold entries of its entities), and whether work arrived while it
    had none. Executors attach, detach, claim and report back; entities notify."""

    __slots__ = ('_entities', '_executor', '_last', '_put', '_unqueued', '_waitables')

    def __init__(
        self,
        entities: Callable[[], Sequence[Scheduled]],
        waitables: Sequence[Scheduled] = (),
    ) -> None:
        # everything that queues itself (timers are found by the executor), and the user
        # waitables among them (which may not say when they get work)
        self._entities = entities
        self._waitables = waitables
        self._executor: ExecutorT | None = None
        self._last: ExecutorT | None = None
        # the attached executor's queue (set last on attach, cleared first on detach)
        self._put: Callable[[Any], None] | None = None
        # an entity got work while the node had no executor: the next attach looks
        self._unqueued = True

    @property
    def executor(self) -> ExecutorT | None:
        """The executor the node is attached to, or None."""
        return self._executor

    @property
    def last_executor(self) -> ExecutorT | None:
        """The executor the node was last attached to (kept after detach, as rclpy keeps a
        node's executor), or None."""
        return self._last

    # -- executors -----------------------------------------------------------------------------
    def attach(self, executor: ExecutorT, put: Callable[[Any], None]) -> None:
        """Run the node's work on `executor`, whose queue takes entities through `put`; what
        got work meanwhile is queued now. The caller has detached it from any other one."""
        entities: Sequence[Scheduled] | None = None
        if self._last is not executor:
            # entries of its entities may sit in another executor's queue: start afresh
            entities = self._entities()
            for entity in entities:
                entity._scheduled = False
            self._last = executor
        # executor before queue: an entity queued from now on is claimed by `executor`
        self._executor = executor
        self._put = put
        if entities is None and self._unqueued:
            entities = self._entities()
        self._unqueued = False
        if entities is None:
            # a node coming back is not searched; waitables that may not say are asked
            for entity in self._waitables:
                if not entity.notifies_itself and not entity._scheduled and entity.has_work():
                    self.notify(entity)
        else:
            for entity in entities:
                if not entity._scheduled and entity.has_work():
                    self.notify(entity)

    def detach(self, executor: ExecutorT) -> None:
        """`executor` stops running the node (no effect if it is attached elsewhere). Entries
        left in its queue are dropped when claimed."""
        if self._executor is not executor:
            return
        self._put = None
        self._executor = None

    def handed_to(self, executor: ExecutorT) -> None:
        """The node was given to `executor` (``node.executor = …``): it is the node's executor
        from now on, also when that executor does not attach the node itself (another make of
        executor, a test's mock), as rclpy's node remembers the executor it was handed."""
        if self._executor is not executor:
            self._last = executor

    def forget(self) -> None:
        """Detached for good: no executor is kept as the node's last one."""
        self._put = None
        self._executor = None
        self._last = None

    def claim(self, executor: ExecutorT, entity: Scheduled) -> bool:
        """Executor thread, `entity` taken from its queue: may `executor` run it? Not if
        the node left: if it comes back here, attach queues the entity again; if it went to
        another executor, that one has taken the entity over."""
        if self._executor is executor:
            return True
        if self._last is executor:
            entity._scheduled = False
            self._unqueued = True
        return False

    def executed(self, entity: Scheduled) -> None:
        """Executor thread, after `entity` ran: clear its flag *before* looking for more
        work, so work that arrives meanwhile is either seen here or queued by `notify`."""
        entity._scheduled = False
        if entity.has_work():
            self.notify(entity)

    @staticmethod
    def hold(entity: Scheduled) -> None:
        """Executor thread: `entity` (a due timer handed to a worker) is not due again for
        anyone until it has run."""
        entity._scheduled = True

    @staticmethod
    def unhold(entity: Scheduled) -> None:
        """Executor thread: `entity` was not run after all; leave it as another executor
        would want to find it."""
        entity._scheduled = False

    def wake(self) -> None:
        """Any thread: make the attached executor, if any, look again (a timer's new
        deadline, a timer added)."""
        executor = self._executor
        if executor is not None:
            executor.wake()

    # -- entities ------------------------------------------------------------------------------
    def notify_if_ready(self, entity: Scheduled) -> None:
        """An entity joined the node: queue it if work waits for it already."""
        if not entity._scheduled and entity.has_work():
            self.notify(entity)

    def notify(self, entity: Scheduled) -> None:
        """Any thread: `entity` got work; queue it on the attached executor (once), or hold
        it as pending work until the next attach."""
        if entity._scheduled:
            return
        put = self._put
        if put is None:
            # no executor: the next attach must look (and, should one attach right now, the
            # second look below queues the work itself, so it is never lost)
            self._unqueued = True
            put = self._put
            if put is None:
                return
        entity._scheduled = True
        put(entity)
