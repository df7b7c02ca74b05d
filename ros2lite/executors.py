"""Executors, as rclpy has them: they own the work of the nodes added to them.

Entities (subscriptions, services, clients, guard conditions) queue themselves on their node's
executor when work arrives; due timers are found by the executor itself. A
`SingleThreadedExecutor` runs everything on the thread that spins it; a
`MultiThreadedExecutor` hands callbacks to a thread pool, running at once only what the
callback groups allow. Coroutine callbacks run as Tasks that keep their group until they end.

`spin_once` runs exactly one callback, as rclpy promises; `spin` and
`spin_until_future_complete` let a subscription deliver a short batch per turn (bounded in count
and time, and ended as soon as the awaited future completes), which is what makes high message
rates affordable in Python.

An idle single-threaded executor whose nodes keep one emptied channel waits in that channel
rather than on its queue (ros2lite.runtime.parking): the next message then wakes the spinning
thread straight from Zenoh, with no doorbell thread between. Anything queued meanwhile
interrupts that wait, and the node's alarm ends it at a timer's or the caller's deadline.
"""

from __future__ import annotations

import inspect
import os
import queue
import threading
import time
import warnings
from collections.abc import Callable, Coroutine, Iterator
from concurrent.futures import ThreadPoolExecutor
from typing import TYPE_CHECKING, Any, cast

from ros2lite.context import Context, default_context
from ros2lite.runtime.executable import RUNNING, Executable
from ros2lite.runtime.parking import QUEUE, Parking
from ros2lite.runtime.scheduling import NodeWork
from ros2lite.task import Future, Task

if TYPE_CHECKING:
    from ros2lite.callback_groups import CallbackGroup
    from ros2lite.node import Node
    from ros2lite.timer import Timer

__all__ = [
    'ConditionReachedException',
    'Executor',
    'ExternalShutdownException',
    'MultiThreadedExecutor',
    'ShutdownException',
    'SingleThreadedExecutor',
    'TimeoutException',
]


class ExternalShutdownException(Exception):
    """Spinning ended because the process was asked to stop (SIGTERM), as in rclpy."""


class ShutdownException(Exception):
    """The executor was shut down."""


class TimeoutException(Exception):
    """No work came within the time given (wait_for_ready_callbacks)."""


class ConditionReachedException(Exception):
    """The condition given to wait_for_ready_callbacks held before work came."""


# a wait shorter than this (seconds) is not parked: the queue's own timed wait is exact, and a
# park would pay the alarm's hand-over to end it
_PARK_MIN = 0.002


class Executor:
    """Runs the callbacks of its nodes; subclasses decide on which threads."""

    # waits in a kept channel when idle (the spinning thread runs every callback itself)
    _parks = True

    def __init__(self, *, context: Context | None = None) -> None:
        self._context = context or default_context()
        self._nodes: list[Node] = []
        self._lock = threading.RLock()
        # entities and tasks with work; None is a bare wake-up
        self._queue: queue.SimpleQueue[Executable | Task | None] = queue.SimpleQueue()
        self._put = self._queue.put
        # the node whose kept channel the spinning thread waits in, and that thread
        self._parked: Parking | None = None
        self._ident = 0
        # entities whose callback group was busy, re-queued when the group frees
        self._blocked: list[Executable] = []
        # a due timer waits for its group: releasing a group must wake the loop
        self._timer_waits = False
        self._is_shutdown = False
        self._spinning = 0
        self._context.add_executor(self)

    @property
    def context(self) -> Context:
        """The context whose nodes this executor runs."""
        return self._context

    # `with SingleThreadedExecutor() as executor:` shuts it down on the way out
    def __enter__(self) -> Executor:
        return self

    def __exit__(self, *exc: object) -> None:
        self.shutdown()

    # -- nodes and tasks -----------------------------------------------------------------------
    def add_node(self, node: Node) -> bool:
        """Take over `node` (a node belongs to one executor at a time)."""
        with self._lock:
            if node in self._nodes:
                return False
            self._nodes.append(node)
        work = node.work
        previous = work.executor
        if previous is not None and previous is not self:
            previous.remove_node(node)
        # what got work while the node had no executor is queued now (NodeWork.attach)
        work.attach(self, self._enqueue)
        node.parking.attach(self)
        if self._spinning:
            self.wake()  # a spinning thread must see the node's timers
        return True

    def remove_node(self, node: Node) -> None:
        """Stop running `node`'s callbacks."""
        with self._lock:
            if node not in self._nodes:
                return
            self._nodes.remove(node)
        node.work.detach(self)
        node.parking.detach(self)

    def get_nodes(self) -> list[Node]:
        """The nodes added to this executor."""
        with self._lock:
            return list(self._nodes)

    def wake(self) -> None:
        """Any thread: make a waiting spin look again (at ok(), timers, conditions)."""
        self._enqueue(None)

    @property
    def parks(self) -> bool:
        """Whether an idle spin waits in a kept channel (parking) instead of its queue."""
        return self._parks

    def keeps_here(self) -> bool:
        """Whether the calling thread is the one spinning this executor, which looks at kept
        channels before it waits (a channel emptied on any other thread is handed back)."""
        return self._parks and threading.get_ident() == self._ident

    def create_task(
        self,
        callback: Callable[..., object] | Coroutine[object, object, object],
        *args: object,
        **kwargs: object,
    ) -> Task:
        """Run `callback(*args, **kwargs)` (or a coroutine) on this executor as a Task."""
        if inspect.iscoroutine(callback):
            coro = callback
            task = Task(lambda: coro, executor=self, reschedule=self._enqueue)
        else:
            assert callable(callback)
            task = Task(callback, args, kwargs, executor=self, reschedule=self._enqueue)
        self._enqueue(task)
        return task

    def shutdown(self, timeout_sec: float | None = None) -> bool:
        """Remove every node and stop spinning (True: done)."""
        self._is_shutdown = True
        for node in self.get_nodes():
            self.remove_node(node)
        self.wake()
        return True

    # -- spinning --------------------------------------------------------------------------------
    def _ok(self) -> bool:
        return self._context.ok() and not self._is_shutdown

    def _check_terminating(self) -> None:
        if self._context.terminating:
            raise ExternalShutdownException()

    def spin(self) -> None:
        """Run callbacks until the context shuts down or shutdown() is called."""
        self._run_until(None, None)
        self._check_terminating()

    def spin_once(self, timeout_sec: float | None = None) -> None:
        """Run one callback (or due timer), waiting up to `timeout_sec` (None: forever)."""
        self._spin_once(timeout_sec, None)

    def _spin_once(self, timeout_sec: float | None, stop: Callable[[], bool] | None) -> None:
        self._check_terminating()
        self._spinning += 1
        try:
            item = self._next(timeout_sec, stop)
            if item is not None:
                self._dispatch(item, False, None)
        finally:
            self._spinning -= 1
        self._check_terminating()

    def spin_until_future_complete(self, future: Future, timeout_sec: float | None = None) -> None:
        """Run callbacks until `future` is done or `timeout_sec` passes (a future completed
        on another thread ends the wait at once)."""
        future.add_done_callback_now(lambda _f: self.wake())
        if self._run_until(future.done, timeout_sec) is None and not future.done():
            self._check_terminating()

    def spin_until(
        self, condition: Callable[[], bool] | None = None, timeout_sec: float | None = None
    ) -> bool:
        """Run callbacks until `condition()` holds or `timeout_sec` passes (None: until
        shutdown); True when the condition ended it. The condition is checked between
        callbacks and whenever the executor is woken, so a callback or another thread (which
        should then call `wake()`) can end the wait at once."""
        ended = self._run_until(condition, timeout_sec)
        if ended is not None:
            return ended
        self._check_terminating()
        return condition is not None and condition()

    def _run_until(self, stop: Callable[[], bool] | None, timeout_sec: float | None) -> bool | None:
        """Run callbacks, a batch per turn, until `stop()` holds (True), `timeout_sec` passes
        (False) or the executor or its context shuts down (None)."""
        deadline = None if timeout_sec is None else time.monotonic() + timeout_sec
        self._spinning += 1
        try:
            while self._ok():
                if stop is not None and stop():
                    return True
                remaining = None if deadline is None else deadline - time.monotonic()
                if remaining is not None and remaining <= 0:
                    return False
                item = self._next(remaining, stop)
                if item is not None:
                    self._dispatch(item, True, stop)
        finally:
            self._spinning -= 1
        return None

    def spin_once_until_future_complete(
        self, future: Future, timeout_sec: float | None = None
    ) -> None:
        """Run one callback, but stop waiting for one as soon as `future` completes (on any
        thread)."""
        if future.done():
            return
        future.add_done_callback_now(lambda _f: self.wake())
        self._spin_once(timeout_sec, future.done)

    def wait_for_ready_callbacks(
        self,
        timeout_sec: float | None = None,
        nodes: list[Node] | None = None,
        condition: Callable[[], bool] | None = None,
    ) -> tuple[Callable[[], None], Executable | Task, Node | None]:
        """Wait for the next piece of work; (run it, the entity or task, its node). Raises
        ShutdownException, TimeoutException or ConditionReachedException when none came.
        (`nodes` is accepted for rclpy's signature; the work of every node is considered.)"""
        if self._is_shutdown:
            raise ShutdownException()
        if condition is not None and condition():
            raise ConditionReachedException()
        item = self._next(timeout_sec, condition)
        if item is None:
            if self._is_shutdown or not self._context.ok():
                raise ShutdownException()
            if condition is not None and condition():
                raise ConditionReachedException()
            raise TimeoutException()
        node = None if type(item) is Task else cast('Node | None', item._node)
        return (lambda: self._dispatch(item, False, None)), item, node

    def _wait_for_ready_callbacks(
        self, timeout_sec: float | None = None, nodes: list[Node] | None = None
    ) -> Iterator[tuple[Callable[[], None], Executable | Task, Node | None]]:
        """rclpy's generator form of :meth:`wait_for_ready_callbacks`."""
        while True:
            yield self.wait_for_ready_callbacks(timeout_sec, nodes)

    # -- finding work ----------------------------------------------------------------------------
    def _due_timer(self) -> tuple[Timer | None, float | None]:
        """A due timer whose group is free, else (None, seconds until the next one)."""
        wait: float | None = None
        for node in self._nodes:
            for timer in node.timers:
                if timer.scheduled:
                    continue
                ns = timer.time_until_next_call()
                if ns is None:
                    continue
                remaining = ns / 1e9
                if remaining <= 0:
                    if timer.callback_group.can_execute(timer):
                        return timer, None
                    self._timer_waits = True
                    continue  # its group's release wakes us
                wait = remaining if wait is None else min(wait, remaining)
        return None, wait

    def _next(
        self, timeout: float | None, stop: Callable[[], bool] | None
    ) -> Executable | Task | None:
        """The next entity, task or due timer; None when the timeout passed, `stop()` holds
        or the executor/context shut down. A bare wake-up is not work: waiting goes on."""
        work = self._queue
        self._ident = threading.get_ident()
        for node in self._nodes:
            if node.timers:
                break
        else:  # no timers (a loop, not any(): no generator per call)
            # hot path: work already queued runs at once, with no deadline arithmetic (and no
            # queue.Empty raised when there is none: one consumer, so empty() is exact)
            if not work.empty():
                item = work.get_nowait()
                if item is not None:
                    return self._queued(item)
                if not self._ok() or (stop is not None and stop()):
                    return None  # (a shutdown's wake-up, taken here, ends the wait)
            while timeout is None:
                item = self._wait(None)
                if item is not None:
                    return item
                if not self._ok() or (stop is not None and stop()):
                    return None
                if any(node.timers for node in self._nodes):
                    break  # a timer was added meanwhile: take the general path
        deadline = None if timeout is None else time.monotonic() + timeout
        while True:
            timer, next_timer = self._due_timer()
            if timer is not None:
                return self._queued(timer)
            wait = None if deadline is None else max(0.0, deadline - time.monotonic())
            if next_timer is not None:
                wait = max(0.0, next_timer) if wait is None else min(wait, max(0.0, next_timer))
            item = self._wait(wait)
            if item is not None:
                return item
            if not self._ok() or (stop is not None and stop()):
                return None
            if deadline is not None and time.monotonic() >= deadline:
                return None

    def _wait(self, wait: float | None) -> Executable | Task | None:
        """Up to `wait` seconds (None: no limit) for the next queued item; None after a bare
        wake-up or when the time passed. Parks in a kept channel when it can."""
        if self._parks:
            parking = self._parking(wait)
            if parking is not None:
                self._parked = parking  # (before it arms: an _enqueue from then on interrupts)
                try:
                    outcome = parking.wait(self, wait, self._queue.empty)
                finally:
                    self._parked = None
                if outcome is not QUEUE:
                    return cast('Executable | None', outcome)
                if not self._ok():
                    return None
        try:
            item = self._queue.get(timeout=wait) if wait != 0 else self._queue.get_nowait()
        except queue.Empty:
            return None
        return None if item is None else self._queued(item)

    def _parking(self, wait: float | None) -> Parking | None:
        """The node whose one kept channel an idle spin may wait in; when there is no single
        one, or the wait is too short to park, or a second thread spins this executor, every
        kept channel goes back to its doorbell."""
        found: Parking | None = None
        count = 0
        for node in self._nodes:
            parking = node.parking
            if parking.keeps:
                kept = parking.kept_for(self)
                if kept:
                    found, count = parking, count + kept
        if count == 1 and not (wait is not None and 0 < wait < _PARK_MIN) and self._spinning <= 1:
            return found
        if count:
            self._hand_back()
        return None

    def _queued(self, item: Executable | Task) -> Executable | Task:
        """`item` (queued work or a due timer) runs next: kept channels go back to their
        doorbells, so a sample that comes while other work keeps the executor busy is queued
        behind that work rather than waiting until the executor is idle again."""
        self._hand_back()
        return item

    def _hand_back(self) -> None:
        for node in self._nodes:
            if node.parking.keeps:
                node.parking.hand_back(self)

    def _enqueue(self, item: Executable | Task | None) -> None:
        """Any thread: queue work (None: a bare wake-up), ending a wait in a kept channel."""
        self._put(item)
        parked = self._parked
        if parked is not None:
            parked.interrupt()

    # -- running work ----------------------------------------------------------------------------
    def _dispatch(
        self, item: Executable | Task, batch: bool, stop: Callable[[], bool] | None
    ) -> None:
        if type(item) is Task:
            self._run_task(item)
            return
        node: Node = item._node  # type: ignore[assignment]  # queued entities have a node
        if not node.work.claim(self, item):
            return  # its node left (NodeWork.claim): not ours to run
        group = item.callback_group
        if item.needs_group and not group.beginning_execution(item):
            with self._lock:
                self._blocked.append(item)
            if group.can_execute(item):  # freed meanwhile: don't wait for a release
                self._release(group, None)
            return
        self._start(item, group, batch, stop)

    def _start(
        self, entity: Executable, group: CallbackGroup, batch: bool, stop: Callable[[], bool] | None
    ) -> None:
        self._run_entity(entity, group, batch, stop)

    def _run_entity(
        self, entity: Executable, group: CallbackGroup, batch: bool, stop: Callable[[], bool] | None
    ) -> None:
        running = RUNNING
        saved = running.executor, running.entity
        running.executor, running.entity = self, entity
        pending: Task | None = None
        try:
            pending = entity.run_pending(batch, stop)
        finally:
            running.executor, running.entity = saved
            entity._node.work.executed(entity)  # type: ignore[union-attr]  # run: has a node
            if entity.needs_group:
                if pending is None or pending.done():
                    self._release(group, entity)
                else:
                    pending.add_done_callback_now(lambda _f: self._release(group, entity))

    def _run_task(self, task: Task) -> None:
        task()
        if task.done() and task.exception() is not None:
            raise task.exception()  # type: ignore[misc]

    def _release(self, group: CallbackGroup, entity: Executable | None) -> None:
        if entity is not None:
            group.ending_execution(entity)
        if self._blocked:
            with self._lock:
                waiting = [e for e in self._blocked if e.callback_group is group]
                if waiting:
                    self._blocked = [e for e in self._blocked if e.callback_group is not group]
            for e in waiting:
                self._enqueue(e)
        if self._timer_waits:
            self._timer_waits = False
            self.wake()  # due timers of the group may run now

    def run_callback(
        self,
        callback: Callable[..., object],
        *args: object,
        then: Callable[[Any], None] | None = None,  # gets what the user's callback returned
    ) -> Task | None:
        """Call a user callback; a coroutine it returns goes on as a Task of this executor
        (first step now). `then(result)` gets the result, now or when the task ends."""
        result = callback(*args)
        if not inspect.iscoroutine(result):
            if then is not None:
                then(result)
            return None
        coro = result
        task = Task(lambda: coro, executor=self, reschedule=self._enqueue)
        if then is not None:
            task.add_done_callback_now(
                lambda t: then(t.result()) if t.exception() is None else None
            )
        self._run_task(task)
        return None if task.done() else task


class SingleThreadedExecutor(Executor):
    """Runs every callback on the thread that spins it."""


# queued by a worker whose callback raised, so the spinning thread raises it at once (never run)
_WORKER_FAILED = Task(lambda: None)


class MultiThreadedExecutor(Executor):
    """Runs callbacks on a pool of `num_threads` threads, as far as callback groups allow.

    An exception in a callback is raised from the spinning call (this one or the next), as
    rclpy does."""

    _parks = False  # callbacks run on workers: channels go back to their doorbells

    def __init__(self, num_threads: int | None = None, *, context: Context | None = None) -> None:
        super().__init__(context=context)
        if num_threads is None:
            # the CPUs this process may run on, as rclpy counts them
            affinity = getattr(os, 'sched_getaffinity', None)
            num_threads = len(affinity(0)) if affinity is not None else (os.cpu_count() or 2)
        elif num_threads < 1:
            raise ValueError('num_threads must be at least 1')
        elif num_threads == 1:
            warnings.warn(
                'MultiThreadedExecutor with one thread runs one callback at a time: '
                'a SingleThreadedExecutor does the same with less overhead',
                UserWarning,
                stacklevel=2,
            )
        self._num_threads = num_threads
        self._executor = ThreadPoolExecutor(num_threads, thread_name_prefix='ros2lite-executor')
        self._errors: queue.SimpleQueue[BaseException] = queue.SimpleQueue()
        self._workers = threading.BoundedSemaphore(num_threads)

    @property
    def num_threads(self) -> int:
        """How many callbacks may run at once."""
        return self._num_threads

    def _raise_errors(self) -> None:
        try:
            error = self._errors.get_nowait()
        except queue.Empty:
            return
        raise error

    def _next(
        self, timeout: float | None, stop: Callable[[], bool] | None
    ) -> Executable | Task | None:
        self._raise_errors()
        item = super()._next(timeout, stop)
        self._raise_errors()
        return item

    def _submit(self, fn: Callable[..., None], *args: object) -> bool:
        """Hand `fn(*args)` to a worker; False if the executor was shut down meanwhile (by
        another thread, while this one was still spinning)."""
        # never queue more work in the pool than it has threads: what waits stays in our
        # queue, where callback groups and node moves are still honoured
        self._workers.acquire()

        def run() -> None:
            try:
                fn(*args)
            except BaseException as e:
                self._errors.put(e)
                self._enqueue(_WORKER_FAILED)
            finally:
                self._workers.release()
                self.wake()

        try:
            self._executor.submit(run)
        except RuntimeError:  # the pool is shut down: the work goes with the executor
            self._workers.release()
            return False
        return True

    def _start(
        self, entity: Executable, group: CallbackGroup, batch: bool, stop: Callable[[], bool] | None
    ) -> None:
        if entity.is_timer:
            NodeWork.hold(entity)  # not due again for us while it runs
        if not self._submit(self._run_entity, entity, group, batch, stop):
            # not run: leave the entity as another executor would want to find it
            NodeWork.unhold(entity)
            if entity.needs_group:
                group.ending_execution(entity)

    def _dispatch(
        self, item: Executable | Task, batch: bool, stop: Callable[[], bool] | None
    ) -> None:
        if item is _WORKER_FAILED:
            self._raise_errors()
            return
        if type(item) is Task:
            self._submit(self._run_task, item)
            return
        super()._dispatch(item, batch, stop)

    def shutdown(self, timeout_sec: float | None = None) -> bool:
        """Stop, and shut the thread pool down (waiting for it unless timeout_sec is 0)."""
        super().shutdown(timeout_sec)
        self._executor.shutdown(wait=timeout_sec is None or timeout_sec > 0)
        return True
