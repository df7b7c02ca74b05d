"""Who runs a node's work, and when: :class:`NodeWork`, the one owner of a node's executor
and of its entities' "queued" flags.

A sample arriving on a Zenoh thread, a node moving between executors (`spin_once(node)` adds
and removes it per call), a multi-threaded worker finishing a callback and an executor being
shut down all meet here, so their order is decided in one place: an entity is queued at most
once until it has run, work that arrives while the node has no executor is held until
`attach`, and an entry left in a former executor's queue is dropped, not run twice.

It also holds the node's *kept* channels (see ros2lite.transport.pull): a subscription that
emptied its channel on an executor that would only wait afterwards leaves the channel with
the node, and that executor waits in it itself instead of on its queue, saving the doorbell's
hand-over. A kept channel stays with the node across `spin_once(node)` calls (which add and
remove the node each time); an executor that cannot park gets them handed back on attach.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable, Sequence
from typing import Any, Generic, Protocol, TypeVar

__all__ = ['Alarm', 'Channel', 'NodeWork', 'Scheduled', 'WorkExecutor']


class Scheduled:
    """Base of what a NodeWork queues (every Executable). Its flag says "in an executor's
    queue, or running"; only this module sets it."""

    _scheduled = False
    # the entity tells its NodeWork whenever it gets work, also while its node has no
    # executor (so attach need not ask it); user waitables that only answer is_ready() do not
    notifies_itself = False
    # going away (set before its channel closes): its node keeps no channel for it
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

    @property
    def parks(self) -> bool:
        """Whether it waits in kept channels itself (single-threaded executors do)."""
        ...

    def wake(self) -> None:
        """Any thread: make a waiting spin look again."""
        ...

    def keeps_here(self) -> bool:
        """Whether the calling thread is the one it spins on, and it would park."""
        ...


class Channel(Protocol):
    """A kept channel as executors use it (ros2lite.transport.pull.PulledSamples)."""

    @property
    def kept(self) -> bool:
        """Still kept (a take() that found a sample, or an undeclare, ends it)."""
        ...

    def poll(self) -> bool:
        """Without waiting: a sample came (now pending; the channel is not kept any more)."""
        ...

    def arm(self) -> None:
        """About to park: interrupts from now on end it."""
        ...

    def disarm(self) -> None:
        """Armed, but will not park after all."""
        ...

    def park(self) -> bool:
        """Wait in the channel: True when a sample came, False when interrupted."""
        ...

    def interrupt(self) -> None:
        """Any thread: end a park."""
        ...

    def release(self) -> None:
        """Hand the channel back to its doorbell."""
        ...


ExecutorT = TypeVar('ExecutorT', bound=WorkExecutor)


class NodeWork(Generic[ExecutorT]):
    """The scheduling state of one node: the executor it is attached to (and the one before,
    whose queue may still hold entries of its entities), and whether work arrived while it
    had none. Executors attach, detach, claim and report back; entities notify."""

    __slots__ = (
        '_entities',
        '_executor',
        '_kept',
        '_last',
        '_lock',
        '_parking',
        '_put',
        '_unqueued',
        '_waitables',
    )

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
        # kept channels, by the entity whose channel it is; the one an executor waits in
        self._kept: dict[Scheduled, Channel] = {}
        self._parking: tuple[WorkExecutor, Scheduled] | None = None
        self._lock = threading.Lock()

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
        if not executor.parks:
            self._hand_back()  # (under the lock that keep() checks the executor under)
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
        left in its queue are dropped when claimed; a wait in one of its channels ends."""
        with self._lock:
            if self._executor is not executor:
                return
            self._put = None
            self._executor = None
            parked = self._parking
            channel = (
                self._kept.get(parked[1]) if parked is not None and parked[0] is executor else None
            )
        if channel is not None:
            channel.interrupt()

    # -- kept channels ---------------------------------------------------------------------------
    @property
    def keeps(self) -> bool:
        """Whether any channel is kept (read unlocked: a hint for the executor's idle path)."""
        return bool(self._kept)

    def keep(self, entity: Scheduled, channel: Channel) -> bool:
        """Consumer thread, `entity` emptied `channel`: may it stay with the node, for the
        executor to wait in? Only for a parking executor that spins on this very thread
        (which looks at kept channels before it waits)."""
        executor = self._executor
        if executor is None or not executor.keeps_here():
            return False
        with self._lock:
            # checked again where attach and destroy change them: a node moved to an
            # executor that does not park, or an entity going away, keeps nothing
            if self._executor is not executor or not executor.parks or entity.destroyed:
                return False
            self._kept[entity] = channel
        return True

    def unkeep(self, entity: Scheduled) -> None:
        """`entity` is going away: forget its kept channel (its undeclare closes it)."""
        with self._lock:
            self._kept.pop(entity, None)

    def kept_count(self, executor: ExecutorT) -> int:
        """Executor thread: how many channels the node keeps for `executor` (0 when the node
        is not its, or another executor is parked in one: a node moved mid-wait). Entries
        whose channel is no longer kept (a take() found a sample, an undeclare closed it)
        are dropped on the way."""
        with self._lock:
            if self._executor is not executor or self._parking is not None:
                return 0
            stale = [entity for entity, channel in self._kept.items() if not channel.kept]
            for entity in stale:
                del self._kept[entity]
            return len(self._kept)

    def release_kept(self, executor: ExecutorT) -> None:
        """Executor thread, about to wait elsewhere: every kept channel goes back to its
        doorbell."""
        with self._lock:
            if self._executor is not executor or self._parking is not None:
                return
            kept, self._kept = self._kept, {}
        for channel in kept.values():
            channel.release()

    def begin_park(self, executor: ExecutorT) -> tuple[Scheduled, Channel] | None:
        """Executor thread: the one kept channel to wait in, armed (interrupts reach it
        from now on); None when the node is not the executor's or keeps not exactly one."""
        with self._lock:
            if self._executor is not executor or self._parking is not None:
                return None
            if len(self._kept) != 1:
                return None
            ((entity, channel),) = self._kept.items()
            channel.arm()
            self._parking = (executor, entity)
            return entity, channel

    def end_park(self, executor: ExecutorT, entity: Scheduled, got: bool) -> bool:
        """Executor thread, its park on `entity` ended (`got`: with a sample): whether it
        may run the entity now. If the node moved meanwhile, the sample (or the channel)
        goes where the node went."""
        with self._lock:
            self._parking = None
            if got:
                self._kept.pop(entity, None)
            if self._executor is executor:
                return got
            new = self._executor
            channel = None if got or new is None or new.parks else self._kept.pop(entity, None)
        if channel is not None:
            channel.release()  # the node's new executor does not park: the doorbell serves it
        elif got:
            self.notify(entity)  # queued where the node is now (or when it is attached)
        elif new is not None:
            new.wake()  # it may park in the channel now
        return False

    def _hand_back(self) -> None:
        """Attach to an executor that does not park: kept channels go back to their
        doorbells, except one another executor is parked in (its end_park hands it back)."""
        with self._lock:
            if not self._kept:
                return
            parked = self._parking
            kept = {e: c for e, c in self._kept.items() if parked is None or e is not parked[1]}
            for entity in kept:
                del self._kept[entity]
            waiting = self._kept.get(parked[1]) if parked is not None else None
        for channel in kept.values():
            channel.release()
        if waiting is not None:
            waiting.interrupt()

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


class Alarm:
    """One thread that calls an action at a deadline, for a wait with no timeout of its own
    (an executor parked in a channel). `set` replaces what is pending and wakes the thread
    only when the new deadline is earlier than the one it sleeps until, so a loop of waits
    with growing deadlines (`spin_once(timeout_sec=…)` in a loop) costs no hand-over each."""

    def __init__(self, name: str) -> None:
        self._cond = threading.Condition(threading.Lock())
        self._deadline = 0.0
        self._action: Callable[[], None] | None = None
        self._sleeping_until = float('inf')
        self._name = name
        self._thread: threading.Thread | None = None
        self._closed = False

    def set(self, deadline: float, action: Callable[[], None]) -> None:
        """Call `action()` at `deadline` (time.monotonic), unless set again or cancelled."""
        with self._cond:
            self._deadline, self._action = deadline, action
            if self._thread is None:
                self._thread = threading.Thread(target=self._run, daemon=True, name=self._name)
                self._thread.start()
            elif deadline < self._sleeping_until:
                self._cond.notify()

    def cancel(self) -> None:
        """Drop what is pending (the thread is not woken; a late call finds nothing)."""
        self._action = None

    def close(self) -> None:
        """End the thread (whatever is pending is dropped)."""
        with self._cond:
            self._action = None
            self._closed = True
            self._cond.notify()

    def _run(self) -> None:
        cond = self._cond
        with cond:
            while not self._closed:
                if self._action is None:
                    self._sleeping_until = float('inf')
                    cond.wait()
                    continue
                remaining = self._deadline - time.monotonic()
                if remaining > 0:
                    self._sleeping_until = self._deadline
                    cond.wait(remaining)
                    continue
                action, self._action = self._action, None
                cond.release()
                try:
                    action()
                finally:
                    cond.acquire()
