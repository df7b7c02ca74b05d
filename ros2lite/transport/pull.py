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
sit idle afterwards may *keep* the emptied channel instead of handing it back (`keeper`), and
then *park*: wait in `recv()` itself, woken by Rust directly, as a raw zenoh program is. Work
for anything else wakes a parked consumer with :meth:`interrupt`: an empty sample without an
attachment, put on the subscriber's own key and kept inside this session. Every receiver here
drops such samples (rmw_zenoh's rule: no attachment, no ROS message), and a KEEP_LAST ring has
one slot more than its depth, so a stray interrupt never pushes out a sample the QoS keeps.
"""

from __future__ import annotations

import contextlib
import threading
from collections import deque
from collections.abc import Callable
from itertools import islice
from operator import attrgetter
from typing import TYPE_CHECKING

import zenoh

from ros2lite.qos import DurabilityPolicy, HistoryPolicy, QoSProfile
from ros2lite.transport.session import (
    declare_subscriber,
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
# a sample without an attachment (an interrupt, or not a ROS message) never enters `pending`,
# where it could push a real one out of a KEEP_LAST deque
_attached = attrgetter('attachment')


class PulledSamples:
    """A subscriber whose consumer pulls batches with `take(limit)` on its own thread.

    `on_ready()` is called (from the doorbell thread) when samples wait and the consumer had
    said it was done; `ready` tells whether samples may be waiting. KEEP_LAST keeps exactly
    the newest `depth` samples not yet taken; KEEP_ALL blocks the publisher (through Zenoh's
    congestion control) once `_CAPACITY` samples wait. Samples without an attachment, which
    rmw_zenoh ignores, are never handed out.
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
        # a transient-local subscriber is zenoh-ext's, with a history of its own: never parked
        self._keeper = None if qos.durability == DurabilityPolicy.TRANSIENT_LOCAL else keeper
        self._kept = False  # emptied, the doorbell asleep, the consumer may park
        self._interrupted = True  # an interrupt is on its way (or nobody is parked)
        self._interrupting = threading.Lock()  # one interrupt per arming, whoever sends it
        channel = self._sub.handler
        self._recv = channel.recv
        self._try_recv = channel.try_recv
        # samples taken from the channel and not yet handed out, oldest first
        self._pending: deque[Sample] = deque(maxlen=self._depth)
        self._armed = True  # the doorbell owns the channel (the consumer found it empty)
        # the doorbell waits on this lock (held) for the consumer to hand the channel back;
        # a bare lock, because threading.Event runs Python code on both sides of every wake
        self._rearm = threading.Lock()
        self._rearm.acquire()
        self._owed = False  # the consumer has taken the channel back and not released it yet
        self._rearm_later = False
        self._on_ready = on_ready
        self._closed = False
        self._thread = threading.Thread(
            target=self._doorbell, daemon=True, name=f'ros2lite-sub {name}'
        )
        self._thread.start()

    @property
    def ready(self) -> bool:
        """Samples may be waiting (so a consumer that stops early must come back)."""
        return not self._armed or bool(self._pending)

    def _doorbell(self) -> None:
        recv, rearm, pending = self._recv, self._rearm, self._pending
        while True:
            try:
                sample = recv()  # GIL released while the channel is empty
            except Exception:
                return  # closed: undeclared, or the session went away
            if not sample.attachment:
                continue  # an interrupt left over, or not a ROS message: wait on
            pending.append(sample)
            self._armed = False  # after the append: a consumer seeing this sees the sample
            self._on_ready()
            rearm.acquire()  # until the consumer has emptied the channel (GIL released)
            if self._closed:
                return

    def _pull(self, limit: int) -> None:
        """Consumer thread, while it owns the channel: move up to what `limit` needs into
        `pending` (KEEP_LAST: all of it, so the ring's newest `depth` survive); when the
        channel runs dry, hand it back to the doorbell (woken now, or by `rearm()` when the
        consumer said it would call that after delivering)."""
        pending = self._pending
        # KEEP_ALL: a chunk at a time, so one-by-one consumers (spin_once) pull rarely
        want = max(limit, _CHUNK) - len(pending) if self._depth is None else self._depth + limit
        it = filter(_attached, iter(self._try_recv, None))
        try:
            if want > 0:
                pending.extend(islice(it, want))
            extra = next(it, None)  # does the channel hold more?
        except Exception:  # closed mid-pull
            extra = None
        if extra is None:
            self._armed = True
            self._owed = True
            if not self._rearm_later:
                self.rearm()
        else:
            pending.append(extra)

    def rearm(self) -> None:
        """Consumer thread, after delivering what `take(…, rearm_later=True)` gave: wake the
        doorbell if the channel ran dry, unless the keeper keeps the channel for the consumer
        to park on. Waking it only now keeps it from taking the GIL in the middle of a
        callback (which costs a delivery its latency)."""
        self._rearm_later = False
        if self._owed and not self._kept:
            keeper = self._keeper
            if (
                keeper is not None
                and not self._closed
                # an interrupt reaches every subscriber of the key in this session
                and sole_subscriber(self._session, self._key)
                and keeper(self)
            ):
                self._kept = True
                return
            self._owed = False
            self._rearm.release()

    # -- a kept channel: the consumer waits on it itself -------------------------------------------
    @property
    def kept(self) -> bool:
        """The consumer keeps the emptied channel (the doorbell sleeps): it must `poll`,
        `park` or `release` it before it waits for work anywhere else. An undeclared
        subscriber's channel is never kept."""
        return self._kept and not self._closed

    def _arrived(self, sample: Sample) -> bool:
        """A sample from the kept channel: a real one ends the keeping (the consumer owns
        the channel, with this sample pending); an interrupt is dropped."""
        if not sample.attachment:
            return False
        self._pending.append(sample)
        self._armed = False
        self._owed = False  # owed again once the consumer has emptied the channel
        self._kept = False
        return True

    def poll(self) -> bool:
        """Consumer thread, kept channel: whether a sample came meanwhile (it is pending
        now, and the channel no longer kept)."""
        try:
            while (sample := self._try_recv()) is not None:
                if self._arrived(sample):
                    return True
        except Exception:  # closed: undeclared, or the session went away
            pass
        return False

    def arm(self) -> None:
        """Consumer thread, kept channel, about to park: interrupts from now on end the
        park (also one that comes before `park()` is called: it then returns at once)."""
        self._interrupted = False

    def disarm(self) -> None:
        """Consumer thread: it armed, and will not park after all."""
        self._interrupted = True

    def park(self) -> bool:
        """Consumer thread, kept and armed channel: wait in `recv()` (GIL released) until a
        sample comes (True, as after `poll`) or :meth:`interrupt` (False). A closed channel
        returns False at once."""
        try:
            while True:
                if self._arrived(self._recv()):
                    return True
                if self._interrupted:
                    return False  # (an older interrupt's sample is dropped on the way)
        except Exception:  # closed
            return False
        finally:
            self._interrupted = True

    def interrupt(self) -> None:
        """Any thread: end a `park()` (once per arming; no effect unless armed)."""
        with self._interrupting:
            if self._interrupted:
                return
            self._interrupted = True
        with contextlib.suppress(Exception):  # closed: the park has ended anyway
            put_local(self._session, self._key)

    def release(self) -> None:
        """Consumer thread (nobody parked): hand a kept channel back to the doorbell."""
        if self._kept:
            self._kept = False
            self._owed = False
            with contextlib.suppress(RuntimeError):  # undeclare released it already
                self._rearm.release()

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
        self._closed = True
        # closes the channel: a doorbell (or a parked consumer) in recv() returns
        undeclare_subscriber(self._session, self._key, self._sub)
        with contextlib.suppress(RuntimeError):  # (not held: the doorbell is in recv())
            self._rearm.release()  # a doorbell waiting for the consumer returns
        if self._thread is not threading.current_thread():
            # a thread still inside zenoh when the interpreter finalises aborts the process
            self._thread.join(timeout=1.0)
