"""NodeWork without a router: an entity is queued once until it has run, work that arrives
while the node has no executor waits for the next attach, and entries left in a former
executor's queue are never run there."""

from __future__ import annotations

import inspect
import sys
import threading
import types

from ros2lite.runtime.scheduling import NodeWork, Scheduled


class FakeExecutor:
    """A queue and a wake-up counter: what a NodeWork asks of an executor."""

    parks = False  # never waits in a kept channel

    def keeps_here(self) -> bool:
        return False

    def __init__(self) -> None:
        self.queue: list[Scheduled] = []
        self.wakes = 0
        self._lock = threading.Lock()

    def put(self, entity: Scheduled) -> None:
        with self._lock:
            self.queue.append(entity)

    def wake(self) -> None:
        self.wakes += 1

    def take(self) -> list[Scheduled]:
        with self._lock:
            taken, self.queue = self.queue, []
        return taken


class Entity(Scheduled):
    """Has work while `pending` > 0; running it takes one piece."""

    def __init__(self, pending: int = 0, *, notifies_itself: bool = True) -> None:
        self.pending = pending
        self.notifies_itself = notifies_itself

    def has_work(self) -> bool:
        return self.pending > 0


def _work(*entities: Entity, waitables: tuple[Entity, ...] = ()) -> NodeWork[FakeExecutor]:
    every = [*entities, *waitables]
    return NodeWork(lambda: every, waitables)


def _run(work: NodeWork[FakeExecutor], executor: FakeExecutor) -> list[Scheduled]:
    """What `executor` runs of its queue (claimed entries), each taking one piece of work."""
    ran = []
    for entity in executor.take():
        if work.claim(executor, entity):
            assert isinstance(entity, Entity)
            entity.pending -= 1
            ran.append(entity)
            work.executed(entity)
    return ran


def test_work_before_attach_is_queued_once_on_attach() -> None:
    sub = Entity()
    work = _work(sub)
    sub.pending = 2
    work.notify(sub)
    work.notify(sub)
    assert not sub.scheduled  # nowhere to queue yet
    executor = FakeExecutor()
    work.attach(executor, executor.put)
    assert executor.queue == [sub] and sub.scheduled
    work.notify(sub)  # already queued: not again
    assert executor.queue == [sub]


def test_executed_requeues_while_work_remains() -> None:
    sub = Entity()
    work = _work(sub)
    executor = FakeExecutor()
    work.attach(executor, executor.put)
    sub.pending = 2
    work.notify(sub)
    assert _run(work, executor) == [sub]
    assert executor.queue == [sub]  # one piece left: requeued by executed()
    assert _run(work, executor) == [sub]
    assert executor.queue == [] and not sub.scheduled


def test_entry_left_in_a_former_queue_is_not_run_and_comes_back_on_reattach() -> None:
    sub = Entity()
    work = _work(sub)
    executor = FakeExecutor()
    work.attach(executor, executor.put)
    sub.pending = 1
    work.notify(sub)
    work.detach(executor)  # spin_once(node) removes the node after its one callback
    assert work.executor is None and work.last_executor is executor
    assert _run(work, executor) == []  # not claimed: the node had left
    assert not sub.scheduled
    work.attach(executor, executor.put)  # back: the pending work is queued again
    assert _run(work, executor) == [sub]


def test_moving_to_another_executor_hands_the_work_over() -> None:
    sub = Entity()
    work = _work(sub)
    first, second = FakeExecutor(), FakeExecutor()
    work.attach(first, first.put)
    sub.pending = 1
    work.notify(sub)
    work.detach(first)
    work.attach(second, second.put)
    assert second.queue == [sub]  # flags reset, the work found again
    assert _run(work, first) == []  # the stale entry: not the first one's any more
    assert sub.scheduled  # ... and it did not touch the flag the second one owns
    assert _run(work, second) == [sub]


def test_detach_by_another_executor_changes_nothing() -> None:
    work = _work()
    first, second = FakeExecutor(), FakeExecutor()
    work.attach(first, first.put)
    work.detach(second)
    assert work.executor is first


def test_waitables_that_do_not_notify_are_asked_on_every_attach() -> None:
    quiet = Entity(notifies_itself=False)
    loud = Entity()
    work = _work(loud, waitables=(quiet,))
    executor = FakeExecutor()
    work.attach(executor, executor.put)
    work.detach(executor)
    quiet.pending = 1  # readied without a word
    loud.pending = 1  # (said nothing either: a notifying entity is not searched)
    work.attach(executor, executor.put)
    assert executor.queue == [quiet]


def test_forget_drops_the_last_executor() -> None:
    sub = Entity()
    work = _work(sub)
    executor = FakeExecutor()
    work.attach(executor, executor.put)
    work.forget()
    assert work.executor is None and work.last_executor is None
    work.wake()
    assert executor.wakes == 0


def test_hold_and_unhold() -> None:
    timer = Entity()
    NodeWork.hold(timer)
    assert timer.scheduled
    NodeWork.unhold(timer)
    assert not timer.scheduled


def test_work_arriving_while_an_executor_attaches_is_queued_at_once() -> None:
    """The narrowest race of the seam, replayed deterministically: a notifier finds no
    executor, and before it can record that work waits, an executor attaches completely
    (and so finds nothing waiting). The notifier must then queue the work itself; waiting
    for the next attach would leave it stranded on a node that spins forever."""
    sub = Entity()
    work = _work(sub)
    executor = FakeExecutor()
    work.attach(executor, executor.put)
    work.detach(executor)  # spin_once(node) done: the node waits for the next call
    lines, start = inspect.getsourcelines(NodeWork.notify)
    (offset,) = [i for i, line in enumerate(lines) if 'self._unqueued = True' in line]
    window = start + offset  # after "no executor" was seen, before it is recorded
    attached: list[bool] = []

    def local(frame: types.FrameType, event: str, arg: object) -> object:
        if event == 'line' and frame.f_lineno == window and not attached:
            attached.append(True)
            work.attach(executor, executor.put)  # the other thread, all at once
        return local

    def tracer(frame: types.FrameType, event: str, arg: object) -> object:
        return local if frame.f_code is NodeWork.notify.__code__ else None

    sub.pending = 1
    sys.settrace(tracer)
    try:
        work.notify(sub)
    finally:
        sys.settrace(None)
    assert attached, 'the window was not reached'
    assert executor.queue == [sub] and sub.scheduled
