"""Where an idle single-threaded executor waits: in its node's *kept* channel, one room for the
whole handshake (:class:`Parking`, one per node).

A typed subscription that emptied its channel on the thread spinning a single-threaded
executor may *keep* the channel with its node instead of handing it back to the doorbell thread
(ros2lite.transport.pull). When that executor would otherwise wait on its queue it *parks*:
:meth:`Parking.wait` waits in the channel's `recv()`, so the next sample wakes the spinning
thread straight from Zenoh, with no doorbell between. Three things end a park early, all
through :meth:`Parking.interrupt`, at most once per park: work queued on the executor, the
node leaving the executor, and a deadline (a timer's, `spin_once`'s), which the node's
:class:`Alarm` keeps. :meth:`Parking.hand_back` gives kept channels back to their doorbells
whenever the executor turns to other work, so a sample arriving meanwhile is queued behind
that work rather than waiting until the executor is idle again.

The node's executor as this room sees it changes only through :meth:`Parking.attach` and
:meth:`Parking.detach` (the executor calls them next to NodeWork's), under the same lock as
:meth:`Parking.keep` reads it: a node moved to an executor that does not park (a
MultiThreadedExecutor), even mid-park, gets every channel back to its doorbell, and a sample
a park took after the move goes where the node went.
"""

from __future__ import annotations

import threading
import time
import weakref
from collections.abc import Callable
from typing import Protocol

from ros2lite.runtime.scheduling import Scheduled

__all__ = ['QUEUE', 'Alarm', 'Channel', 'Parker', 'Parking']


class Channel(Protocol):
    """A kept channel (ros2lite.transport.pull.PulledSamples) as the park uses it."""

    @property
    def kept(self) -> bool:
        """Still kept (a sample taken outside a park, or an undeclare, ends it)."""
        ...

    def poll(self) -> bool:
        """Without waiting: a sample came (now pending; the channel is not kept any more)."""
        ...

    def park(self) -> bool:
        """Wait in the channel: True when a sample came, False on an interrupt or close."""
        ...

    def interrupt(self) -> None:
        """Any thread: make a `park()` return False."""
        ...

    def release(self) -> None:
        """Any thread, nobody parked: hand the channel back to its doorbell."""
        ...


class Parker(Protocol):
    """An executor as the park sees it (ros2lite.executors.Executor)."""

    @property
    def parks(self) -> bool:
        """Whether it waits in kept channels at all (single-threaded executors do)."""
        ...

    def keeps_here(self) -> bool:
        """Whether the calling thread is the one it spins on, and it would park."""
        ...

    def wake(self) -> None:
        """Any thread: make a waiting spin look again."""
        ...


class _Queue:
    """The answer of a wait that did not wait: the executor's queue decides."""


QUEUE = _Queue()


class Parking:
    """The kept channels of one node and the park in them (see the module doc). `notify`
    queues an entity where the node now is (NodeWork.notify)."""

    def __init__(self, notify: Callable[[Scheduled], None]) -> None:
        self._notify = notify
        self._lock = threading.Lock()
        self._executor: Parker | None = None
        # kept channels, by the entity whose channel it is
        self._kept: dict[Scheduled, Channel] = {}
        # the park going on: its executor, entity and channel; armed until interrupted
        self._parked: tuple[Parker, Scheduled, Channel] | None = None
        self._armed = False
        self._alarm: Alarm | None = None

    @property
    def keeps(self) -> bool:
        """Whether any channel is kept (read unlocked: a hint for the executor's idle path)."""
        return bool(self._kept)

    @property
    def waiting_in(self) -> Channel | None:
        """The channel a park waits in now, if any."""
        parked = self._parked
        return parked[2] if parked is not None else None

    # -- where the node is (the executor, next to NodeWork.attach/detach) -------------------------
    def attach(self, executor: Parker) -> None:
        """The node runs on `executor` now. One that does not park gets every kept channel
        back to its doorbell; a park another executor has going on ends (its end hands that
        channel on)."""
        if executor.parks:  # (`spin_once(node)` attaches per call: no lock on this path)
            self._executor = executor
            return
        with self._lock:
            self._executor = executor
            if not self._kept:
                return
            parked = self._parked
            given = [c for e, c in self._kept.items() if parked is None or e is not parked[1]]
            self._kept = {parked[1]: parked[2]} if parked is not None else {}
            waiting = self._disarm()
        for channel in given:
            channel.release()
        if waiting is not None:
            waiting.interrupt()

    def detach(self, executor: Parker) -> None:
        """`executor` stops running the node (no effect if it is attached elsewhere): its
        park in one of the node's channels ends."""
        with self._lock:
            if self._executor is not executor:
                return
            self._executor = None
            waiting = self._disarm()
        if waiting is not None:
            waiting.interrupt()

    def close(self) -> None:
        """The node is destroyed: the alarm's thread ends."""
        alarm, self._alarm = self._alarm, None
        if alarm is not None:
            alarm.close()

    # -- the consumer: keeping a channel -------------------------------------------------------
    def keep(self, entity: Scheduled, channel: Channel) -> bool:
        """Consumer thread, `entity` emptied `channel`: may it stay with the node, for the
        executor to wait in? Only for a parking executor that spins on this very thread
        (which looks at kept channels before it waits), and not for an entity going away."""
        executor = self._executor
        if executor is None or not executor.keeps_here():
            return False
        with self._lock:
            if self._executor is not executor or entity.destroyed:
                return False
            self._kept[entity] = channel
        return True

    def unkeep(self, entity: Scheduled) -> None:
        """`entity` is going away: forget its kept channel (its undeclare closes it)."""
        with self._lock:
            self._kept.pop(entity, None)

    # -- the executor: waiting, handing back ------------------------------------------------------
    def kept_for(self, executor: Parker) -> int:
        """Executor thread: how many channels the node keeps for `executor` (0 when the node
        is not its, or a park is going on: a node moved mid-wait). Channels no longer kept
        are forgotten on the way."""
        with self._lock:
            if self._executor is not executor or self._parked is not None:
                return 0
            kept = self._kept
            for entity in [e for e, channel in kept.items() if not channel.kept]:
                del kept[entity]
            return len(kept)

    def hand_back(self, executor: Parker) -> None:
        """Executor thread, about to wait elsewhere or run other work: every kept channel
        goes back to its doorbell."""
        with self._lock:
            if self._executor is not executor or self._parked is not None or not self._kept:
                return
            kept, self._kept = self._kept, {}
        for channel in kept.values():
            channel.release()

    def wait(
        self, executor: Parker, timeout: float | None, idle: Callable[[], bool]
    ) -> Scheduled | _Queue | None:
        """Executor thread: wait up to `timeout` seconds (None: no limit; 0: only look) in
        the node's one kept channel. The entity whose sample came, to run now; None when the
        wait ended without one (interrupted, or the time passed); QUEUE when it did not wait
        (no single kept channel; `idle()` False once armed, i.e. work is queued; a look that
        found nothing). Interrupts reach the park from the moment `idle()` is asked."""
        with self._lock:
            if self._executor is not executor or self._parked is not None or len(self._kept) != 1:
                return QUEUE
            ((entity, channel),) = self._kept.items()
            self._parked = (executor, entity, channel)
            self._armed = True
        got = False
        try:
            if not idle():
                return QUEUE
            if timeout == 0:
                got = channel.poll()
            elif timeout is None:
                got = self._park(channel)
            else:
                alarm = self._alarm
                if alarm is None:
                    alarm = self._alarm = Alarm('ros2lite-park-alarm')
                    weakref.finalize(self, alarm.close)  # its thread ends with the node
                alarm.set(time.monotonic() + timeout, self.interrupt)
                try:
                    got = self._park(channel)
                finally:
                    alarm.cancel()
        finally:
            run = self._end(executor, entity, got)
        if run:
            return entity
        return QUEUE if timeout == 0 else None

    def interrupt(self) -> None:
        """Any thread: end the park going on, if any (once per park)."""
        with self._lock:
            waiting = self._disarm()
        if waiting is not None:
            waiting.interrupt()

    def _disarm(self) -> Channel | None:
        """Under the lock: the channel a park waits in, to interrupt (once per park)."""
        if not self._armed or self._parked is None:
            return None
        self._armed = False
        return self._parked[2]

    def _park(self, channel: Channel) -> bool:
        """Wait in `channel` until a sample (True), or this park's interrupt or a close
        (False); an interrupt meant for an earlier park is waited past."""
        while not channel.park():
            if not self._armed or not channel.kept:
                return False
        return True

    def _end(self, executor: Parker, entity: Scheduled, got: bool) -> bool:
        """The park on `entity` ended (`got`: with a sample): whether `executor` may run the
        entity now. If the node moved meanwhile, the sample (or the channel) goes where the
        node went."""
        with self._lock:
            self._parked = None
            self._armed = False
            if got:
                self._kept.pop(entity, None)
            if self._executor is executor:
                return got
            new = self._executor
            channel = None if got or new is None or new.parks else self._kept.pop(entity, None)
        if channel is not None:
            channel.release()  # the node's new executor does not park: the doorbell serves it
        elif got:
            self._notify(entity)  # queued where the node is now (or when it is attached)
        elif new is not None:
            new.wake()  # it may park in the channel now
        return False


class Alarm:
    """One thread that calls an action at a deadline, for a wait with no timeout of its own
    (a park in a channel). `set` replaces what is pending and wakes the thread only when the
    new deadline is earlier than the one it sleeps until, so a loop of waits with growing
    deadlines (`spin_once(timeout_sec=…)` in a loop) costs no hand-over each."""

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
            if self._closed:
                return
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
