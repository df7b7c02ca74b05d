"""The one seam to Zenoh: every declaration, put, query and reply the library makes.

The rest of the library hands in key expressions, QoS profiles, bytes and callbacks, and gets
back small handles; it never imports zenoh.  Received data stays as the Zenoh object only
where copying it out would cost the hot path a Python loop per sample (subscription batches,
see :class:`SampleReceiver`); there the caller reads it through :class:`Sample`.

Callbacks given here run on Zenoh's own threads, so they must only queue work (the executor
runs user code), never block.
"""

from __future__ import annotations

import contextlib
import os
import threading
import time
from collections import deque
from collections.abc import Callable, Iterable
from itertools import chain, filterfalse, islice
from operator import attrgetter, methodcaller
from typing import cast

import zenoh
import zenoh.ext

from ros2lite.qos import DurabilityPolicy, HistoryPolicy, QoSProfile, ReliabilityPolicy
from ros2lite.transport.handles import Handle, Payload, Sample, Session
from ros2lite.transport.history import HistoryBoundedPublisher
from ros2lite.transport.keys import liveliness_subscription_key
from ros2lite.transport.shm import ShmPublisher, shm_publisher

__all__ = [
    "Handle",
    "HistoryBoundedPublisher",
    "Publisher",
    "Querier",
    "Request",
    "Sample",
    "SampleReceiver",
    "Session",
    "as_zenoh",
    "declare_filter",
    "declare_liveliness_subscriber",
    "declare_local_publisher",
    "declare_publisher",
    "declare_querier",
    "declare_queryable",
    "declare_token",
    "foreign_unattached",
    "is_interrupt",
    "liveliness_answer",
    "liveliness_keys",
    "put_local",
    "sole_subscriber",
    "undeclare_quietly",
    "undeclare_subscriber",
]


Publisher = zenoh.Publisher | HistoryBoundedPublisher | ShmPublisher
"""A declared publisher: `.put(payload, attachment=…)` and `.undeclare()`."""


_Subscriber = (
    zenoh.Subscriber[zenoh.handlers.Handler[zenoh.Sample]]
    | zenoh.ext.AdvancedSubscriber[zenoh.handlers.Handler[zenoh.Sample]]
)


def as_zenoh(session: Session) -> zenoh.Session:
    """The zenoh session behind the library's handle (only zenoh sessions are ever opened:
    see :func:`ros2lite.transport.open.open_session`)."""
    return cast(zenoh.Session, session)


def undeclare_quietly(*handles: Handle | None) -> None:
    """Undeclare what is given; errors only mean the session is already closed."""
    for handle in handles:
        if handle is not None:
            with contextlib.suppress(Exception):
                handle.undeclare()


# -- graph ----------------------------------------------------------------------------------------
def declare_token(session: Session, key: str) -> Handle:
    """A liveliness token: the graph sees the entity it names while the token lives."""
    return as_zenoh(session).liveliness().declare_token(key)


def liveliness_keys(session: Session, domain_id: int, timeout: float = 5.0) -> list[str]:
    """Keys of every live token of the domain, from one complete liveliness query."""
    return liveliness_answer(session, domain_id, timeout)[0]


def liveliness_answer(
    session: Session, domain_id: int, timeout: float = 5.0
) -> tuple[list[str], bool]:
    """The keys of one liveliness query, and whether it ended before its time-out: a query
    the time-out ends has only the replies that came until then (a router with tens of
    thousands of tokens can take longer)."""
    start = time.monotonic()
    # an explicit large channel: the default handler can stall past a few hundred replies
    replies = (
        as_zenoh(session)
        .liveliness()
        .get(
            liveliness_subscription_key(domain_id),
            zenoh.handlers.FifoChannel(1 << 16),
            timeout=timeout,
        )
    )
    keys = []
    for reply in replies:
        sample = reply.ok
        if sample is not None:
            keys.append(str(sample.key_expr))
    # Zenoh closes the channel either when every queryable has answered or at the time-out
    return keys, time.monotonic() - start < timeout * 0.95


def declare_liveliness_subscriber(
    session: Session, domain_id: int | None, on_change: Callable[[str, bool], None]
) -> Handle:
    """`on_change(key, alive)` for every token of the domain (None: of every domain)
    appearing or going away, starting with the ones alive now (history)."""
    put = zenoh.SampleKind.PUT

    def callback(sample: zenoh.Sample) -> None:
        on_change(str(sample.key_expr), sample.kind == put)

    sub: Handle = (
        as_zenoh(session)
        .liveliness()
        .declare_subscriber(
            liveliness_subscription_key(domain_id), zenoh.handlers.Callback(callback), history=True
        )
    )
    return sub


# -- topics ---------------------------------------------------------------------------------------
def _reliable(qos: QoSProfile) -> bool:
    return qos.reliability != ReliabilityPolicy.BEST_EFFORT


def _transient_local(qos: QoSProfile) -> bool:
    return qos.durability == DurabilityPolicy.TRANSIENT_LOCAL


def declare_publisher(session: Session, key: str, qos: QoSProfile) -> Publisher:
    """A publisher with `.put(payload, attachment=…)`, mapped from QoS as rmw_zenoh does:
    reliability, BLOCK congestion control only for reliable KEEP_ALL, and transient local
    through zenoh-ext's advanced publisher (a cache of `depth` samples, forgotten after its
    lifespan, or once its bytes pass HISTORY_BYTES: :class:`HistoryBoundedPublisher`)."""
    reliable = _reliable(qos)
    block = reliable and qos.history == HistoryPolicy.KEEP_ALL
    reliability = zenoh.Reliability.RELIABLE if reliable else zenoh.Reliability.BEST_EFFORT
    congestion = zenoh.CongestionControl.BLOCK if block else zenoh.CongestionControl.DROP
    if _transient_local(qos):
        # as rmw_zenoh: reliable + transient local also announces its last sequence number
        # (sporadic heartbeat), which subscribers' heartbeat recovery relies on
        miss = (
            zenoh.ext.MissDetectionConfig(heartbeat=None, sporadic_heartbeat=0.5)
            if reliable
            else None
        )

        def make() -> zenoh.ext.AdvancedPublisher:
            return zenoh.ext.declare_advanced_publisher(
                as_zenoh(session),
                key,
                cache=zenoh.ext.CacheConfig(max(qos.depth, 1)),
                sample_miss_detection=miss,
                publisher_detection=True,
                reliability=reliability,
                congestion_control=congestion,
            )

        span = qos.lifespan
        lifespan = None if span.is_unspecified or span.is_infinite else span.nanoseconds / 1e9
        history = HistoryBoundedPublisher(make, lifespan, max(qos.depth, 1))
        return shm_publisher(session, history.put, history.undeclare) or history
    plain = as_zenoh(session).declare_publisher(
        key, reliability=reliability, congestion_control=congestion
    )
    return shm_publisher(session, plain.put, plain.undeclare) or plain


# subscribers declared per (session, key expression): an interrupt (put_local) reaches every
# subscriber of its key in the session, so only a key's sole subscriber may be parked in
_subscribers: dict[tuple[int, str], int] = {}
_subscribers_lock = threading.Lock()


def sole_subscriber(session: Session, key: str) -> bool:
    """Whether exactly one subscriber of this session listens on `key` (see put_local)."""
    return _subscribers.get((id(session), key), 0) == 1


def _count_subscriber(session: Session, key: str, change: int) -> None:
    with _subscribers_lock:
        n = _subscribers.get((id(session), key), 0) + change
        if n > 0:
            _subscribers[(id(session), key)] = n
        else:
            _subscribers.pop((id(session), key), None)


def undeclare_subscriber(session: Session, key: str, subscriber: Handle) -> None:
    """Undeclare a subscriber made by declare_subscriber (errors: the session is closed)."""
    _count_subscriber(session, key, -1)
    undeclare_quietly(subscriber)


def declare_subscriber(
    session: Session,
    key: str,
    qos: QoSProfile,
    handler: zenoh.handlers.FifoChannel[zenoh.Sample] | zenoh.handlers.RingChannel[zenoh.Sample],
    *,
    local_only: bool = False,
) -> _Subscriber:
    """A subscriber feeding `handler` (a zenoh channel), mapped from QoS as rmw_zenoh does:
    transient local through zenoh-ext's advanced subscriber, which asks late-joining
    publishers for their cache (and, when reliable, recovers missed samples by heartbeat).
    `local_only`: a plain subscriber hearing only this session's puts (the ring behind a
    filter, ros2lite.transport.pull). Undeclare it with undeclare_subscriber."""
    _count_subscriber(session, key, +1)
    if local_only:
        return as_zenoh(session).declare_subscriber(
            key, handler, allowed_origin=zenoh.Locality.SESSION_LOCAL
        )
    if _transient_local(qos):
        recovery = (
            zenoh.ext.RecoveryConfig(periodic_queries=None, heartbeat=True)
            if _reliable(qos)
            else None
        )
        return zenoh.ext.declare_advanced_subscriber(
            as_zenoh(session),
            key,
            handler,
            history=zenoh.ext.HistoryConfig(
                detect_late_publishers=True, max_samples=max(qos.depth, 1)
            ),
            recovery=recovery,
            subscriber_detection=True,
        )
    return as_zenoh(session).declare_subscriber(key, handler)


# the payload of this process's interrupts: a secret, so a peer's empty sample (which a flood
# may send by the million) is never mistaken for one and is reported instead of dropped unheard
_INTERRUPT = os.urandom(16)


def put_local(session: Session, key: str) -> None:
    """An interrupt on `key`, for this session's own subscribers only: a sample without an
    attachment that wakes a consumer waiting in a channel's `recv()` (ros2lite.transport.pull).
    Every receiver drops it, as rmw_zenoh drops samples without an attachment;
    :func:`foreign_unattached` tells it from a peer's."""
    as_zenoh(session).put(key, _INTERRUPT, allowed_destination=zenoh.Locality.SESSION_LOCAL)


def declare_filter(
    session: Session, key: str, qos: QoSProfile, callback: Callable[[zenoh.Sample], None]
) -> Handle:
    """A subscriber calling `callback(sample)` on Zenoh's receive thread (a GIL hold per
    sample: only for filtering, ros2lite.transport.pull). Transient local: zenoh-ext's, with
    recovery but no history query (it replaces a subscriber that had the history already)."""
    _count_subscriber(session, key, +1)
    handler = zenoh.handlers.Callback(callback, indirect=False)
    if _transient_local(qos):
        recovery = (
            zenoh.ext.RecoveryConfig(periodic_queries=None, heartbeat=True)
            if _reliable(qos)
            else None
        )
        advanced: Handle = zenoh.ext.declare_advanced_subscriber(
            as_zenoh(session), key, handler, recovery=recovery, subscriber_detection=True
        )
        return advanced
    plain: Handle = as_zenoh(session).declare_subscriber(key, handler)
    return plain


def is_interrupt(payload: Payload) -> bool:
    """Whether a sample without an attachment carries this process's interrupt."""
    return len(payload) == len(_INTERRUPT) and payload.to_bytes() == _INTERRUPT


def declare_local_publisher(session: Session, key: str) -> zenoh.Publisher:
    """A publisher whose puts reach only this session's subscribers (a filter passing
    samples on, ros2lite.transport.pull)."""
    return as_zenoh(session).declare_publisher(
        key, allowed_destination=zenoh.Locality.SESSION_LOCAL
    )


def foreign_unattached(samples: Iterable[Sample]) -> int:
    """How many of `samples` have no attachment and are not our interrupts (a peer's), in
    C-level maps: a flood brings them by the hundred thousand a second."""
    unattached = list(filterfalse(_attachment_of, samples))
    if not unattached:
        return 0
    ours = sum(map(_INTERRUPT.__eq__, map(_to_bytes, map(_payload_of, unattached))))
    return len(unattached) - ours


_attachment_of = attrgetter("attachment")
_payload_of = attrgetter("payload")
_to_bytes = methodcaller("to_bytes")


# Rust-side queue between zenoh and the pump thread (never below the QoS depth), and how many
# samples the pump moves per GIL hold: up to a whole channel (about 1 ms of work), because a
# pump that gives the GIL back mid-drain waits a switch interval (5 ms) to get it again
# while the executor is busy, and meanwhile the full channel stalls zenoh's receive thread
_CHANNEL_CAPACITY = 4096


class SampleReceiver:
    """A subscriber whose samples land in `buffer`, moved there by a pump thread of its own.

    A zenoh callback per sample would make a second Python thread take the GIL for every
    sample while the executor thread runs user code; that ping-pong was most of the cost of
    a message. Instead samples wait in a Rust-side channel and the pump moves everything
    waiting while holding the GIL once, then calls `on_batch()` (which schedules delivery).
    Each is stored as `(sample, arrival ns)` (raw consumers such as `topic hz` need arrival
    times); a `hook(sample)` replaces the buffer entirely (monitors that must see every
    sample at arrival, a typed waiter that keeps the first message). Samples without an
    attachment never take a slot of the buffer; a peer's are counted to `on_unattached`.
    """

    def __init__(
        self,
        session: Session,
        key: str,
        qos: QoSProfile,
        buffer: deque[tuple[Sample, int]],  # (sample, arrival ns)
        on_batch: Callable[[], None],
        *,
        hook: Callable[[Sample], None] | None = None,
        name: str = "",
        on_unattached: Callable[[int], None] | None = None,
    ) -> None:
        keep_all = qos.history == HistoryPolicy.KEEP_ALL
        capacity = max(qos.depth, _CHANNEL_CAPACITY)
        handler = (
            zenoh.handlers.FifoChannel(capacity)
            if keep_all
            else zenoh.handlers.RingChannel(capacity)
        )  # KEEP_LAST may drop the oldest
        self._sub = declare_subscriber(session, key, qos, handler)
        self._session, self._key = session, key
        self._buffer = buffer
        self._on_batch = on_batch
        self._hook = hook
        self._on_unattached = on_unattached
        self._now = time.time_ns
        self._thread = threading.Thread(
            target=self._pump, args=(self._sub.handler,), daemon=True, name=f"ros2lite-sub {name}"
        )
        self._thread.start()

    def _pump(self, channel: zenoh.handlers.Handler[zenoh.Sample]) -> None:
        """Block (GIL released) until a sample comes, then move the whole backlog at once.
        Ends when the subscriber is undeclared (the channel closes)."""
        recv = channel.recv
        append = self._buffer.append
        now, hook, on_batch = self._now, self._hook, self._on_batch
        while True:
            try:
                first = recv()
            except Exception:
                return  # channel closed: subscription destroyed or session closed
            # what else is waiting, up to a channel's worth: try_recv until it gives None
            rest = islice(iter(channel.try_recv, None), _CHANNEL_CAPACITY - 1)
            try:
                if hook is not None:
                    for sample in chain((first,), rest):
                        try:
                            hook(sample)
                        except Exception:
                            import traceback

                            traceback.print_exc()
                    continue
                batch = [first, *rest]
                real = list(filter(_attachment_of, batch))
                if len(real) != len(batch):  # never a slot of the buffer: dropped, reported
                    foreign = foreign_unattached(batch)
                    if foreign and self._on_unattached is not None:
                        self._on_unattached(foreign)
                for sample in real:
                    append((sample, now()))
                if not real:
                    continue
            except Exception:
                pass  # closed mid-batch; the next recv() ends the thread
            on_batch()

    def undeclare(self) -> None:
        """Stop receiving; the pump thread ends."""
        undeclare_subscriber(self._session, self._key, self._sub)  # ends the pump thread
        if self._thread is not threading.current_thread():
            # a pump still inside zenoh when the interpreter finalises aborts the process
            self._thread.join(timeout=1.0)


# -- services -------------------------------------------------------------------------------------
class Request:
    """One incoming query: its payload and attachment, and the way to answer it once."""

    __slots__ = ("_query", "attachment", "key", "payload")

    def __init__(self, query: zenoh.Query, key: str) -> None:
        self._query: zenoh.Query | None = query
        self.key = key
        payload = query.payload
        attachment = query.attachment
        self.payload = payload.to_bytes() if payload is not None else b""
        self.attachment = attachment.to_bytes() if attachment is not None else None

    def reply(self, payload: bytes, attachment: bytes) -> None:
        """Answer on the service key and finalise the query (the client stops waiting)."""
        query, self._query = self._query, None
        if query is None:
            raise RuntimeError("this request has already been answered")
        try:
            query.reply(self.key, payload, attachment=attachment)
        finally:
            query.drop()

    def drop(self) -> None:
        """Finalise without an answer (the client's query ends with no reply)."""
        query, self._query = self._query, None
        if query is not None:
            query.drop()


def declare_queryable(session: Session, key: str, on_request: Callable[[Request], None]) -> Handle:
    """A service server's queryable: `complete=True`, because rmw_zenoh clients query with
    target ALL_COMPLETE and would never reach an incomplete one."""

    def on_query(query: zenoh.Query) -> None:
        on_request(Request(query, key))

    queryable: Handle = as_zenoh(session).declare_queryable(
        key, zenoh.handlers.Callback(on_query), complete=True
    )
    return queryable


class Querier:
    """A service client's querier: one query per request (ALL_COMPLETE, no consolidation)."""

    def __init__(self, session: Session, key: str, timeout: float | None) -> None:
        self._session, self._key = as_zenoh(session), key
        target, consolidation = zenoh.QueryTarget.ALL_COMPLETE, zenoh.ConsolidationMode.NONE
        if timeout is not None:
            self._querier = as_zenoh(session).declare_querier(
                key, target=target, consolidation=consolidation, timeout=timeout
            )
        else:  # the session's queries_default_timeout applies
            self._querier = as_zenoh(session).declare_querier(
                key, target=target, consolidation=consolidation
            )

    def get(
        self,
        payload: bytes,
        attachment: bytes,
        on_reply: Callable[[bytes, bytes | None], None],
        on_end: Callable[[str | None], None],
    ) -> None:
        """Send one request. `on_reply(payload, attachment)` per answer; `on_end(error)` once
        the query is over (error: the text of an error reply or timeout, else None)."""
        error: list[str] = []

        def reply(r: zenoh.Reply) -> None:
            ok = r.ok
            if ok is None:
                err = r.err
                error.append(
                    err.payload.to_bytes().decode("utf-8", "replace")
                    if err is not None
                    else "error reply"
                )
                return
            att = ok.attachment
            on_reply(ok.payload.to_bytes(), att.to_bytes() if att is not None else None)

        self._querier.get(
            zenoh.handlers.Callback(reply, lambda: on_end(error[0] if error else None)),
            payload=payload,
            attachment=attachment,
        )

    def ask(
        self, payload: bytes, attachment: bytes, timeout: float | None = None
    ) -> tuple[bytes, bytes | None] | str:
        """Send one request and wait for its first answer on the calling thread, in the
        reply channel's `recv()` (GIL released, Ctrl-C ends it), so Zenoh's receive thread
        wakes the caller itself: (payload, attachment), or, when the query ended unanswered,
        the text of its error reply ('' for none: no server, or the query's timeout). A
        `timeout` (seconds) is this query's own: it is sent as a one-off query of the same
        key, target and consolidation, which Zenoh ends at that time."""
        handler = zenoh.handlers.FifoChannel(4)
        if timeout is None:
            replies = self._querier.get(handler, payload=payload, attachment=attachment)
        else:
            replies = self._session.get(
                self._key,
                handler,
                target=zenoh.QueryTarget.ALL_COMPLETE,
                consolidation=zenoh.ConsolidationMode.NONE,
                timeout=max(timeout, 0.001),
                payload=payload,
                attachment=attachment,
            )
        error = ""
        for reply in replies:  # ends when the query does
            ok = reply.ok
            if ok is not None:
                att = ok.attachment
                return ok.payload.to_bytes(), att.to_bytes() if att is not None else None
            err = reply.err
            if err is not None:
                error = err.payload.to_bytes().decode("utf-8", "replace")
        return error

    def undeclare(self) -> None:
        """Withdraw the querier."""
        undeclare_quietly(self._querier)


def declare_querier(session: Session, key: str, timeout: float | None) -> Querier:
    """A service client's querier; `timeout` None keeps the session's default."""
    return Querier(session, key, timeout)
