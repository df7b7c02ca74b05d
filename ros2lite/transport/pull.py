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

from ros2lite.qos import HistoryPolicy, QoSProfile
from ros2lite.transport.session import declare_subscriber, undeclare_quietly

if TYPE_CHECKING:
    from ros2lite.transport.handles import Sample, Session

__all__ = ['PulledSamples']

# a KEEP_ALL channel's capacity: a burst this long waits in Rust, then zenoh pushes back
_CAPACITY = 4096
# how many samples a KEEP_ALL consumer pulls at least once it pulls
_CHUNK = 64
_NONE = type(None)
_attachment_of = attrgetter('attachment')


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
    ) -> None:
        keep_all = qos.history == HistoryPolicy.KEEP_ALL
        depth = max(qos.depth, 1)
        self._depth = None if keep_all else depth
        handler: (
            zenoh.handlers.FifoChannel[zenoh.Sample] | zenoh.handlers.RingChannel[zenoh.Sample]
        ) = (
            zenoh.handlers.FifoChannel(max(qos.depth, _CAPACITY))
            if keep_all
            else zenoh.handlers.RingChannel(depth)  # the ring drops the oldest
        )
        self._sub = declare_subscriber(session, key, qos, handler)
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
        it = iter(self._try_recv, None)
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
        doorbell if the channel ran dry. Waking it only now keeps it from taking the GIL in
        the middle of a callback (which costs a delivery its latency)."""
        self._rearm_later = False
        if self._owed:
            self._owed = False
            self._rearm.release()

    def take(self, limit: int, *, rearm_later: bool = False) -> list[Sample]:
        """Consumer thread: up to `limit` samples, oldest first (fewer, or none, when fewer
        wait). With `rearm_later` the caller must call `rearm()` once it has delivered them."""
        self._rearm_later = rearm_later
        pending = self._pending
        # `_armed` is read before `pending` (see _doorbell); KEEP_LAST always drains the
        # ring first, so that what is handed out is the newest `depth`
        if not self._armed and (self._depth is not None or len(pending) < limit):
            self._pull(limit)
        n = min(limit, len(pending))
        try:
            if n == 1:
                sample = pending.popleft()
                return [] if sample.attachment is None else [sample]
            if n <= 0:
                return []
            batch = list(islice(iter(pending.popleft, None), n))
        except IndexError:  # cleared meanwhile (destroyed)
            return []
        if _NONE in set(map(type, map(_attachment_of, batch))):
            batch = [s for s in batch if s.attachment is not None]
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
        undeclare_quietly(self._sub)  # closes the channel: a doorbell in recv() returns
        with contextlib.suppress(RuntimeError):  # (not held: the doorbell is in recv())
            self._rearm.release()  # a doorbell waiting for the consumer returns
        if self._thread is not threading.current_thread():
            # a thread still inside zenoh when the interpreter finalises aborts the process
            self._thread.join(timeout=1.0)
