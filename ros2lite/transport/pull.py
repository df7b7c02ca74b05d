"""Samples that the consuming thread pulls from Zenoh itself: the typed-subscription hot path.

zenoh-python gives the GIL back inside every `recv()` and `try_recv()`. A pump thread that
moves samples while the executor thread runs callbacks therefore trades the GIL with it per
sample, and every trade costs a thread switch (or, while the executor holds on, a switch
interval). A raw zenoh program is fast because one Python thread does everything; so here the
executor thread pulls the samples it is about to deliver straight from the Rust channel, and
a *doorbell* thread only waits (in `recv()`, GIL released) while the channel is empty. When a
sample comes the doorbell hands it over, tells the consumer (`on_ready`) and sleeps until the
consumer has emptied the channel again: at any moment exactly one of the two owns the
channel, so samples keep their order and nobody competes for the GIL during a burst.

Payloads and attachments stay Zenoh objects until the consumer reads them, and the consumer
reads a batch through C-level iterators (:func:`ros2lite.runtime.delivery.payloads`).

One message at a time, the doorbell is a thread hand-over of its own on every delivery (Rust
wakes the doorbell, the doorbell wakes the executor). So a consumer whose executor would only
sit idle afterwards may *keep* the emptied channel instead of handing it back (`keeper`, which
asks the node's ros2lite.runtime.parking.Parking), and wait in it itself: :meth:`park` is a
`recv()` woken by Rust directly, as a raw zenoh program is, and :meth:`interrupt` ends it with
an *interrupt*, a sample put on the subscriber's own key and kept inside this session. A
KEEP_LAST ring has one slot more than its depth for it, so an interrupt never pushes out a
sample the QoS keeps.

Who owns the channel is one flag under one lock: `_owes` is set by the doorbell before it
hands a sample over and cleared by whoever gives the channel back (the consumer emptying it, a
kept channel handed back, an undeclare), so the doorbell is woken exactly once per hand-over,
whatever the threads race to do.

Samples without an attachment are no ROS message (rmw_zenoh drops them) and are never handed
out. Our own interrupts are dropped silently; any other (a peer's, perhaps a flood) is counted
to `on_unattached`, which reports it.
"""

from __future__ import annotations

import contextlib
import threading
from collections import deque
from collections.abc import Callable, Sequence
from itertools import islice
from operator import attrgetter
from typing import TYPE_CHECKING

import zenoh

from ros2lite.qos import DurabilityPolicy, HistoryPolicy, QoSProfile
from ros2lite.transport.session import (
    declare_subscriber,
    foreign_unattached,
    put_local,
    sole_subscriber,
    undeclare_subscriber,
)

if TYPE_CHECKING:
    from ros2lite.transport.handles import Sample, Session

__all__ = ['PulledSamples']

# a KEEP_ALL channel's capacity: a burst this long waits in Rust, then zenoh pushes back
_CAPACITY = 4096
# how many samples a KEEP_ALL consumer pulls at least once it pulls
_CHUNK = 64
# how many more the doorbell drains at once after a sample without attachment (a flood's
# come in thousands: one GIL hold and one report for them all)
_DRAIN = 4096
# a sample without an attachment (an interrupt, or not a ROS message) never enters `pending`,
# where it could push a real one out of a KEEP_LAST deque
_attached = attrgetter('attachment')


class PulledSamples:
    """A subscriber whose consumer pulls batches with `take(limit)` on its own thread.

    `on_ready()` is called (from the doorbell thread) when samples wait and the consumer had
    said it was done; `ready` tells whether samples may be waiting. KEEP_LAST keeps exactly
    the newest `depth` samples not yet taken; KEEP_ALL blocks the publisher (through Zenoh's
    congestion control) once `_CAPACITY` samples wait. Samples without an attachment, which
    rmw_zenoh ignores, are never handed out; `on_unattached(n)` hears of those that were not
    our own interrupts (any thread).
    """

    def __init__(
        self,
        session: Session,
        key: str,
        qos: QoSProfile,
        on_ready: Callable[[], None],
        *,
        name: str = '',
        keeper: Callable[[PulledSamples], bool] | None = None,
        on_unattached: Callable[[int], None] | None = None,
    ) -> None:
        keep_all = qos.history == HistoryPolicy.KEEP_ALL
        depth = max(qos.depth, 1)
        self._depth = None if keep_all else depth
        handler: (
            zenoh.handlers.FifoChannel[zenoh.Sample] | zenoh.handlers.RingChannel[zenoh.Sample]
        ) = (
            zenoh.handlers.FifoChannel(max(qos.depth, _CAPACITY))
            if keep_all
            # the ring drops the oldest; its spare slot is for an interrupt (see above)
            else zenoh.handlers.RingChannel(depth + 1)
        )
        self._sub = declare_subscriber(session, key, qos, handler)
        self._session, self._key = session, key
        # a transient-local subscriber is zenoh-ext's, with a history of its own: never kept
        self._keeper = None if qos.durability == DurabilityPolicy.TRANSIENT_LOCAL else keeper
        self._on_unattached = on_unattached
        channel = self._sub.handler
        self._recv = channel.recv
        self._try_recv = channel.try_recv
        # samples taken from the channel and not yet handed out, oldest first
        self._pending: deque[Sample] = deque(maxlen=self._depth)
        self._armed = True  # the doorbell owns the channel (the consumer found it empty)
        # the doorbell waits on this lock (held) for the channel to come back; a bare lock,
        # because threading.Event runs Python code on both sides of every wake
        self._rearm = threading.Lock()
        self._rearm.acquire()
        # who owns the channel, and whether it is kept or closed, change together under this
        self._handover = threading.Lock()
        self._owes = False  # the doorbell waits for the channel back (it is the consumer's)
        self._kept = False  # the consumer keeps it emptied, to wait in it itself
        self._closed = False
        # consumer thread only: it found the channel dry and gives it back at rearm()
        self._dry = False
        self._rearm_later = False
        self._on_ready = on_ready
        self._thread = threading.Thread(
            target=self._doorbell, daemon=True, name=f'ros2lite-sub {name}'
        )
        self._thread.start()

    @property
    def ready(self) -> bool:
        """Samples may be waiting (so a consumer that stops early must come back)."""
        return not self._armed or bool(self._pending)

    def _doorbell(self) -> None:
        recv, try_recv, rearm, pending = self._recv, self._try_recv, self._rearm, self._pending
        handover = self._handover
        while True:
            try:
                sample = recv()  # GIL released while the channel is empty
                if sample.attachment:
                    real = [sample]
                else:  # an interrupt left over, or not a ROS message (a flood?)
                    batch = [sample, *islice(iter(try_recv, None), _DRAIN)]
                    real = list(filter(_attached, batch))
                    self._unattached(batch)
                    if not real:
                        continue
            except Exception:
                return  # closed: undeclared, or the session went away
            with handover:
                if self._closed:
                    return
                self._owes = True  # the consumer's from now on, until it gives it back
            pending.extend(real)
            self._armed = False  # after the append: a consumer seeing this sees the sample
            self._on_ready()
            rearm.acquire()  # until the channel comes back (GIL released)
            if self._closed:
                return

    def _give_back(self, *, only_kept: bool = False) -> None:
        """Any thread: wake the doorbell if it waits for the channel (once per hand-over,
        whoever calls); with `only_kept`, only a kept channel."""
        with self._handover:
            if not self._owes or (only_kept and not self._kept):
                return
            self._owes = False
            self._kept = False
        self._rearm.release()

    def _unattached(self, samples: Sequence[Sample]) -> None:
        """Samples without an attachment among `samples`: our interrupts go unheard, a peer's
        are told to `on_unattached`."""
        report = self._on_unattached
        if report is not None:
            foreign = foreign_unattached(samples)
            if foreign:
                report(foreign)

    def _pull(self, limit: int) -> None:
        """Consumer thread, while it owns the channel: move up to what `limit` needs into
        `pending` (KEEP_LAST: all of it, so the ring's newest `depth` survive); when the
        channel runs dry, give it back to the doorbell (now, or at `rearm()` when the consumer
        said it would call that after delivering)."""
        pending = self._pending
        # KEEP_ALL: a chunk at a time, so one-by-one consumers (spin_once) pull rarely; one
        # more than wanted tells whether the channel holds more
        want = max(limit, _CHUNK) - len(pending) if self._depth is None else self._depth + limit
        want = max(want, 0)
        try:
            raw = list(islice(iter(self._try_recv, None), want + 1))
        except Exception:  # closed mid-pull
            raw = []
        attached = list(filter(_attached, raw))
        pending.extend(attached)
        if len(attached) != len(raw):
            self._unattached(raw)
        if len(raw) <= want:  # try_recv found it empty
            self._armed = True
            self._dry = True
            if not self._rearm_later:
                self.rearm()

    def rearm(self) -> None:
        """Consumer thread, after delivering what `take(…, rearm_later=True)` gave: wake the
        doorbell if the channel ran dry, unless the keeper keeps the channel for the consumer
        to wait in. Waking it only now keeps it from taking the GIL in the middle of a
        callback (which costs a delivery its latency)."""
        self._rearm_later = False
        if not self._dry:
            return
        self._dry = False
        keeper = self._keeper
        # an interrupt reaches every subscriber of the key in this session: only a sole one
        if keeper is not None and sole_subscriber(self._session, self._key):
            with self._handover:
                keep = self._owes and not self._closed
                self._kept = keep
            if keep and keeper(self):
                return
        self._give_back()

    # -- a kept channel: the consumer waits in it itself -------------------------------------------
    @property
    def kept(self) -> bool:
        """The consumer keeps the emptied channel (the doorbell sleeps): it must `poll`,
        `park` or `release` it before it waits for work anywhere else. An undeclared
        subscriber's channel is never kept."""
        return self._kept and not self._closed

    def _arrived(self, samples: list[Sample]) -> None:
        """Real samples from the kept channel end the keeping: the consumer owns the channel
        (the doorbell still waits for it), with these pending."""
        with self._handover:
            self._kept = False
        self._pending.extend(samples)
        self._armed = False

    def _sorted(self, sample: Sample) -> bool | None:
        """Kept channel, `sample` (without an attachment) and what else waits now read from
        it: True when real samples came too (pending now), False when one of ours was an
        interrupt, None when all were a peer's (reported)."""
        batch = [sample, *islice(iter(self._try_recv, None), _DRAIN)]
        real = list(filter(_attached, batch))
        foreign = foreign_unattached(batch)
        if foreign and self._on_unattached is not None:
            self._on_unattached(foreign)
        if real:
            self._arrived(real)
            return True
        return False if foreign < len(batch) else None

    def poll(self) -> bool:
        """Consumer thread, kept channel: whether a sample came meanwhile (it is pending
        now, and the channel no longer kept)."""
        try:
            while (sample := self._try_recv()) is not None:
                if sample.attachment:
                    self._arrived([sample])
                    return True
                if self._sorted(sample):
                    return True
        except Exception:  # closed: undeclared, or the session went away
            pass
        return False

    def park(self) -> bool:
        """Consumer thread, kept channel: wait in `recv()` (GIL released) until a sample
        comes (True, as after `poll`) or an interrupt (False: whether it was the awaited one
        is the waiter's to know). A closed channel returns False at once; a peer's samples
        without an attachment are dropped and reported on the way."""
        recv = self._recv
        try:
            while True:
                sample = recv()
                if sample.attachment:
                    self._arrived([sample])
                    return True
                came = self._sorted(sample)
                if came is not None:
                    return came
        except Exception:  # closed
            return False

    def interrupt(self) -> None:
        """Any thread: end a `park()` (an interrupt that finds nobody parked is dropped by
        the next one to read the channel)."""
        with contextlib.suppress(Exception):  # closed: the park has ended anyway
            put_local(self._session, self._key)

    def release(self) -> None:
        """Any thread, nobody parked: hand a kept channel back to the doorbell."""
        self._give_back(only_kept=True)

    def take(self, limit: int, *, rearm_later: bool = False) -> list[Sample]:
        """Consumer thread: up to `limit` samples, oldest first (fewer, or none, when fewer
        wait). With `rearm_later` the caller must call `rearm()` once it has delivered them."""
        self._rearm_later = rearm_later
        pending = self._pending
        if self._kept:  # a take outside the executor's wait (rclpy's Subscription.take)
            self.poll()
        # `_armed` is read before `pending` (see _doorbell); KEEP_LAST always drains the
        # ring first, so that what is handed out is the newest `depth`
        if not self._armed and (self._depth is not None or len(pending) < limit):
            self._pull(limit)
        n = min(limit, len(pending))
        try:
            if n == 1:
                sample = pending.popleft()
                return [sample]
            if n <= 0:
                return []
            batch = list(islice(iter(pending.popleft, None), n))
        except IndexError:  # cleared meanwhile (destroyed)
            return []
        return batch

    def put_back(self, samples: list[Sample]) -> None:
        """Consumer thread: samples taken but not delivered go back to the front (KEEP_LAST
        keeps only those that still fit behind newer arrivals)."""
        pending = self._pending
        if self._depth is not None:
            room = max(self._depth - len(pending), 0)
            if room < len(samples):
                samples = samples[len(samples) - room :] if room else []
        pending.extendleft(reversed(samples))

    def clear(self) -> None:
        """Drop what was taken from the channel and not handed out."""
        self._pending.clear()

    def undeclare(self) -> None:
        """Stop receiving; the doorbell thread ends."""
        with self._handover:
            self._closed = True
        # closes the channel: a doorbell (or a parked consumer) in recv() returns
        undeclare_subscriber(self._session, self._key, self._sub)
        self._give_back()  # a doorbell waiting for the channel returns
        if self._thread is not threading.current_thread():
            # a thread still inside zenoh when the interpreter finalises aborts the process
            self._thread.join(timeout=1.0)
