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
to `on_unattached`, which reports it. In the Rust ring, though, a peer's would take the slots
of real samples: a flood of them pushes real ones out before Python sees them. So the first
time one is seen the subscription puts a *filter* in front of its ring (:class:`_Filter`): a
callback on Zenoh's receive thread that drops them there and passes real samples (and our
interrupts) on to a ring of its own, on a key only this session hears. That costs a Python
call per sample (the GIL on the receive thread), so it is only done once a peer has shown it
sends such samples, and then kept for the subscription's life; a flood then slows the link it
comes on, not the subscription.
"""

from __future__ import annotations

import contextlib
import itertools
import threading
import time
from collections import Counter, deque
from collections.abc import Callable, MutableSequence, Sequence
from itertools import islice
from operator import attrgetter
from typing import TYPE_CHECKING

import zenoh

from ros2lite.qos import DurabilityPolicy, HistoryPolicy, QoSProfile
from ros2lite.transport.session import (
    declare_filter,
    declare_local_publisher,
    declare_subscriber,
    foreign_unattached,
    is_interrupt,
    put_local,
    sole_subscriber,
    undeclare_quietly,
    undeclare_subscriber,
)

if TYPE_CHECKING:
    from ros2lite.transport.handles import Handle, Payload, Sample, Session

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
# the filter reports a flood's samples at the first and then once per this many
_REPORT_EVERY = 4096
_filter_ids = itertools.count()


class _Filter:
    """Zenoh's receive thread, every sample of the key: a peer's samples without an attachment
    are counted and dropped here, before any bounded queue; real ones and our interrupts go on
    to the subscription's own ring through a session-local publisher (no copy: the payload is
    Zenoh's). While the ring is being switched over, samples are held, and those the old ring
    already held dropped (by attachment and payload: the same sample carries the same); a
    peer's unattached ones of that moment are counted once, whichever ring heard them."""

    def __init__(
        self, session: Session, ring_key: str, on_unattached: Callable[[int], None] | None
    ) -> None:
        self._publisher = declare_local_publisher(session, ring_key)
        self._report = on_unattached
        self._foreign = 0  # counted, not yet reported
        self._counted = 0
        self._lock = threading.Lock()
        self._held: list[Sample] | None = []
        # payloads of a peer's unattached samples while held: the old ring may hold them too
        self._held_foreign: Counter[bytes] = Counter()
        # (attachment, payload) of what the old ring held, until a second after start()
        self._seen: set[tuple[bytes, bytes]] = set()
        # payloads of a peer's unattached samples the old ring held and this filter had not
        # met yet: one Zenoh hands a sample to both subscribers in turn, so those that come
        # here within a tenth of a second are counted already (the ones that reached the old
        # ring before this filter was declared never come: a flood meanwhile is undercounted
        # by at most what they were, rather than counted twice)
        self._seen_foreign: Counter[bytes] = Counter()
        self._seen_foreign_until = 0.0
        self._seen_until = 0.0
        self.subscriber: Handle | None = None  # on the subscription's key, set by its owner

    def __call__(self, sample: zenoh.Sample) -> None:
        attachment = sample.attachment
        if attachment is None:
            if is_interrupt(sample.payload):
                self._publisher.put(sample.payload)
                return
            if self._held is not None:
                with self._lock:
                    if self._held is not None and len(self._held_foreign) < _CAPACITY:
                        self._held_foreign[sample.payload.to_bytes()] += 1
                        return
            if self._seen_foreign and self._counted_already(sample.payload):
                return
            self._counted += 1
            self._foreign += 1
            if self._counted == 1 or self._foreign >= _REPORT_EVERY:
                self.flush()
            return
        if self._seen and self._duplicate(sample, attachment):
            return
        if self._held is not None:
            with self._lock:
                held = self._held
                if held is not None:
                    held.append(sample)
                    return
        if self._foreign:
            self.flush()
        self._publisher.put(sample.payload, attachment=attachment)

    def _duplicate(self, sample: Sample, attachment: Payload) -> bool:
        """Whether the old ring held this sample too (each is held once, so it is forgotten
        when met; the old ring's last arrivals come here within moments, so after a second
        nothing is compared any more)."""
        if time.monotonic() > self._seen_until:
            self._seen = set()
            return False
        ident = (attachment.to_bytes(), sample.payload.to_bytes())
        if ident in self._seen:
            self._seen.discard(ident)
            return True
        return False

    def _counted_already(self, payload: Payload) -> bool:
        """Whether the old ring held this peer's unattached sample too (counted there)."""
        if time.monotonic() > self._seen_foreign_until:
            self._seen_foreign = Counter()
            return False
        key = payload.to_bytes()
        if self._seen_foreign[key] > 0:
            self._seen_foreign[key] -= 1
            return True
        return False

    def flush(self) -> None:
        """Report what was counted and not reported yet."""
        n, self._foreign = self._foreign, 0
        if n and self._report is not None:
            self._report(n)

    def start(self, drained: Sequence[Sample], drained_foreign: Sequence[bytes] = ()) -> None:
        """The old ring is drained (`drained`, what it held; `drained_foreign`, the payloads
        of a peer's unattached samples among them, counted by the caller): pass on what was
        held meanwhile, save those, and count the unattached ones the old ring did not have."""
        with self._lock:
            held_foreign, self._held_foreign = self._held_foreign, Counter()
            drained_counts = Counter(drained_foreign)
            new = sum((held_foreign - drained_counts).values())
            # those the old ring heard first and this filter has still to meet
            self._seen_foreign = drained_counts - held_foreign
            self._seen_foreign_until = time.monotonic() + 0.1
            if new:
                self._counted += new
                self._foreign += new
            self._seen = {
                (attachment.to_bytes(), sample.payload.to_bytes())
                for sample in drained
                if (attachment := sample.attachment) is not None
            }
            self._seen_until = time.monotonic() + 1.0
            held, self._held = self._held or [], None
            for sample in held:
                attachment = sample.attachment
                if attachment is not None and not self._duplicate(sample, attachment):
                    self._publisher.put(sample.payload, attachment=attachment)
        self.flush()

    def undeclare(self) -> None:
        """Stop passing on (after its subscriber is undeclared) and report the rest."""
        undeclare_quietly(self._publisher)
        self.flush()


def _until_closed(try_recv: Callable[[], Sample | None]) -> list[Sample]:
    """What an undeclared subscriber's channel still holds, read until it says it is closed
    (Zenoh closes it once no delivery to it is under way any more; a second at most)."""
    out: list[Sample] = []
    deadline = time.monotonic() + 1.0
    while True:
        try:
            sample = try_recv()
        except Exception:  # closed, and empty
            return out
        if sample is not None:
            out.append(sample)
        elif time.monotonic() > deadline:
            return out
        else:
            time.sleep(0.0005)


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
        # the ring drops the oldest; its spare slot is for an interrupt (see above)
        self._size = max(qos.depth, _CAPACITY) if keep_all else depth + 1
        self._sub = declare_subscriber(session, key, qos, self._channel())
        self._session, self._key, self._qos = session, key, qos
        self._ring_key = key  # where the ring listens: the key, or the filter's own one
        self._filter: _Filter | None = None
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

    def _channel(
        self,
    ) -> zenoh.handlers.FifoChannel[zenoh.Sample] | zenoh.handlers.RingChannel[zenoh.Sample]:
        if self._depth is None:
            return zenoh.handlers.FifoChannel(self._size)
        return zenoh.handlers.RingChannel(self._size)

    @property
    def ready(self) -> bool:
        """Samples may be waiting (so a consumer that stops early must come back)."""
        return not self._armed or bool(self._pending)

    def _doorbell(self) -> None:
        rearm, pending, handover = self._rearm, self._pending, self._handover
        while True:
            # read anew each time: the channel changes when a filter is put in front of it
            recv, try_recv = self._recv, self._try_recv
            try:
                sample = recv()  # GIL released while the channel is empty
                real: list[Sample]
                if sample.attachment:
                    real = [sample]
                else:  # an interrupt left over, or not a ROS message (a flood?)
                    batch = [sample, *islice(iter(try_recv, None), _DRAIN)]
                    real = list(filter(_attached, batch))
                    self._unattached(batch, real)
                    if not real and not pending:
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

    def _unattached(self, samples: Sequence[Sample], after: MutableSequence[Sample]) -> None:
        """Whoever owns the channel: samples without an attachment among `samples`. Our
        interrupts go unheard; a peer's are told to `on_unattached`, and the first puts the
        filter in front of the ring, the real samples left in the old ring appended to
        `after` (they came after `samples`)."""
        foreign = foreign_unattached(samples)
        if not foreign:
            return
        if self._filter is None:  # first: the ring's real samples are being pushed out meanwhile
            self._filter_from_now(after)
        if self._on_unattached is not None:
            self._on_unattached(foreign)

    def _filter_from_now(self, into: MutableSequence[Sample]) -> None:
        """The owner of the channel: move the ring behind a filter (see _Filter). The filter
        hears the key before the old ring is drained (into `into`), and drops what that held."""
        if self._closed:
            return
        session, qos = self._session, self._qos
        ring_key = f'{self._key}/@ros2lite_filtered/{next(_filter_ids)}'
        sieve = _Filter(session, ring_key, self._on_unattached)
        # it holds what comes until start(); transient local: without the history, which
        # the old subscriber had already
        sieve.subscriber = declare_filter(session, self._key, qos, sieve)
        ring = declare_subscriber(session, ring_key, qos, self._channel(), local_only=True)
        old, old_try_recv = self._sub, self._try_recv
        self._sub, self._filter = ring, sieve
        self._recv, self._try_recv = ring.handler.recv, ring.handler.try_recv
        self._ring_key = ring_key
        if self._depth is None:
            # undeclared first, then read until closed: a delivery already under way when
            # the filter came (a put routed before it) still lands in the old channel, kept
            undeclare_subscriber(session, self._key, old)
            raw = _until_closed(old_try_recv)
        else:
            # Zenoh deletes a ring with what it holds when its subscriber goes, so it is read
            # before, twice: a delivery still under way after that is lost (KEEP_LAST only,
            # and only at this moment)
            raw = []
            with contextlib.suppress(Exception):  # closed meanwhile (undeclared)
                raw += islice(iter(old_try_recv, None), self._size)
                time.sleep(0.001)
                raw += islice(iter(old_try_recv, None), self._size)
            undeclare_subscriber(session, self._key, old)
        real = list(filter(_attached, raw))
        # a peer's, still in the old ring: counted too (the filter counts only the others)
        drained = [
            sample.payload.to_bytes()
            for sample in raw
            if sample.attachment is None and not is_interrupt(sample.payload)
        ]
        if drained and self._on_unattached is not None:
            self._on_unattached(len(drained))
        into.extend(real)  # the caller hands them out as its own, after what it read
        sieve.start(real, drained)

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
            self._unattached(raw, pending)
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
        if keeper is not None and sole_subscriber(self._session, self._ring_key):
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
        if foreign:
            self._unattached(batch, real)
        if real or self._pending:
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
        try:
            while True:
                sample = self._recv()
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
            put_local(self._session, self._ring_key)

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
        sieve = self._filter
        if sieve is not None:
            if sieve.subscriber is not None:
                undeclare_subscriber(self._session, self._key, sieve.subscriber)
            sieve.undeclare()
        # closes the channel: a doorbell (or a parked consumer) in recv() returns
        undeclare_subscriber(self._session, self._ring_key, self._sub)
        self._give_back()  # a doorbell waiting for the channel returns
        if self._thread is not threading.current_thread():
            # a thread still inside zenoh when the interpreter finalises aborts the process
            self._thread.join(timeout=1.0)
