"""Subscriptions: samples are buffered per subscription and delivered by an executor."""

from __future__ import annotations

import struct
import threading
import time
from collections import deque
from collections.abc import Callable
from dataclasses import dataclass
from itertools import chain, islice
from typing import Any

from ros2lite.endpoint import Endpoint, EndpointOwner, is_transient_local
from ros2lite.transport.keys import EntityKind
from ros2lite.transport.qos import HistoryPolicy, QoSProfile, ReliabilityPolicy


@dataclass(frozen=True)
class MessageInfo:
    """Delivery metadata from the rmw_zenoh attachment, plus our receive time."""

    source_timestamp: int           # ns since the epoch, from the publisher
    received_timestamp: int         # ns since the epoch, when the sample arrived here
    publication_sequence_number: int
    publisher_gid: bytes


_CURRENT_ATTACHMENT = struct.Struct('<qqB')
# Rust-side queue between zenoh and the pump thread (never below the QoS depth), and how many
# samples the pump moves per GIL hold: up to a whole channel (about 1 ms of work), because a
# pump that gives the GIL back mid-drain waits a switch interval (5 ms) to get it again
# while the executor is busy, and meanwhile the full channel stalls zenoh's receive thread
_CHANNEL_CAPACITY = 4096
_PUMP_BATCH = _CHANNEL_CAPACITY
# longest run of callbacks of one subscription in one executor turn (seconds)
_BATCH_TIME = 0.002


def _info(attachment: bytes, received: int) -> MessageInfo:
    # the current 33-byte layout is unpacked inline (hot path); anything else goes through
    # the full decoder, which also reads the legacy keyed layout
    if len(attachment) == 33 and attachment[16] == 16:
        seq, stamp, _ = _CURRENT_ATTACHMENT.unpack_from(attachment)
        return MessageInfo(stamp, received, seq, attachment[17:])
    from ros2lite.transport.attachment import decode_attachment
    try:
        a = decode_attachment(attachment)
    except ValueError:
        return MessageInfo(0, received, 0, b'')
    return MessageInfo(a.source_timestamp, received, a.sequence_number, a.source_gid)


class Subscription(EndpointOwner):
    """Calls `callback(msg)`; with raw=True calls `callback(cdr_bytes, MessageInfo)`."""

    def __init__(self, node: Any, msg_type: Any, topic: str, callback: Callable[..., Any],
                 qos: QoSProfile | int, *, raw: bool = False) -> None:
        import zenoh
        self._ep = _SubscriptionEndpoint(node, msg_type, topic, qos)
        ep = self._ep
        self.callback = callback
        self.raw = raw
        self._work = node.context.work
        keep_all = ep.qos.history == HistoryPolicy.KEEP_ALL
        # zenoh samples as they came: `sample` for typed subscriptions, `(sample, arrival ns)`
        # for raw ones (tools like `topic hz` need arrival times). Bytes are copied out on the
        # executor thread, keeping the pump thread's share of the GIL small.
        self._buffer: deque[Any] = deque(
            maxlen=None if keep_all else max(ep.qos.depth, 1))
        # Samples wait in a Rust-side channel and our own pump thread moves them to the
        # buffer in batches (see _pump). A zenoh callback per sample instead makes a second
        # Python thread take the GIL for every sample while the executor thread runs user
        # code; that GIL ping-pong was most of the cost of a message.
        capacity = max(ep.qos.depth, _CHANNEL_CAPACITY)
        handler = zenoh.handlers.FifoChannel(capacity) if keep_all \
            else zenoh.handlers.RingChannel(capacity)   # KEEP_LAST may drop the oldest
        session = node.context.session
        self._sub: Any
        if is_transient_local(ep.qos):
            import zenoh.ext
            recovery = zenoh.ext.RecoveryConfig(periodic_queries=None, heartbeat=True) \
                if ep.qos.reliability != ReliabilityPolicy.BEST_EFFORT else None
            self._sub = zenoh.ext.declare_advanced_subscriber(
                session, ep.key, handler,
                history=zenoh.ext.HistoryConfig(detect_late_publishers=True,
                                                max_samples=max(ep.qos.depth, 1)),
                recovery=recovery, subscriber_detection=True)
        else:
            self._sub = session.declare_subscriber(ep.key, handler)
        self._deserialize: Any = None
        self._destroyed = False
        self._scheduled = False
        self._pump_thread = threading.Thread(
            target=self._pump, args=(self._sub.handler,), daemon=True,
            name=f'ros2lite-sub {ep.topic_name}')
        self._pump_thread.start()
        ep._announce()

    def _pump(self, channel: Any) -> None:
        """Pump thread: block (GIL released) until a sample comes, then move everything
        waiting in the channel to the buffer while holding the GIL once, so a burst costs
        one GIL hand-off per batch instead of one per sample. Ends when the subscriber is
        undeclared (the channel closes)."""
        recv = channel.recv
        # a subclass hook (e.g. topic monitors) sees every sample; ours is inlined below
        hook = None if type(self)._on_sample is Subscription._on_sample else self._on_sample
        append, extend, put = self._buffer.append, self._buffer.extend, self._work.put
        now, raw = time.time_ns, self.raw
        while True:
            try:
                first = recv()
            except Exception:
                return   # channel closed: subscription destroyed or session closed
            # what else is waiting, up to a batch: try_recv until it gives None
            rest = islice(iter(channel.try_recv, None), _PUMP_BATCH - 1)
            try:
                if hook is not None:
                    for sample in chain((first,), rest):
                        try:
                            hook(sample)
                        except Exception:
                            import traceback
                            traceback.print_exc()
                    continue
                if raw:
                    append((first, now()))
                    for sample in rest:
                        append((sample, now()))
                else:
                    append(first)
                    extend(rest)   # typed: the whole batch moves without a Python loop
            except Exception:
                pass   # closed mid-batch; the next recv() ends the thread
            if not self._scheduled and not self._destroyed:
                self._scheduled = True
                put(self)

    def _on_sample(self, sample: Any) -> None:
        """Pump thread: keep the sample and make sure the executor will come for it.

        The subscription sits in the work queue at most once while it has samples (the
        `_scheduled` flag), so a burst costs one queue entry, not one per sample. Samples
        without an attachment, which rmw_zenoh ignores, are dropped when taken (checking here
        would cost every sample a trip into zenoh on this thread)."""
        if self._destroyed:
            return
        self._buffer.append((sample, time.time_ns()) if self.raw else sample)
        if not self._scheduled:
            self._scheduled = True
            self._work.put(self)

    def _reschedule(self) -> None:
        # Clear the flag *before* looking at the buffer: a sample appended meanwhile is then
        # either seen here or re-queued by the pump, never left behind.
        self._scheduled = False
        if self._buffer and not self._destroyed:
            self._scheduled = True
            self._work.put(self)

    def _deserializer(self) -> Any:
        des = self._deserialize
        if des is None:
            from ros2lite.interfaces.cdr import codec
            from ros2lite.interfaces.registry import default_registry
            des = self._deserialize = codec(self._ep.type_name,
                                            default_registry()).fast_deserializer()
        return des

    def take(self) -> tuple[Any, MessageInfo] | None:
        """The oldest buffered sample as (message or bytes, info), or None. For typed
        subscriptions `received_timestamp` is the time of the take."""
        while True:
            try:
                entry = self._buffer.popleft()
            except IndexError:
                return None
            sample, received = entry if self.raw else (entry, time.time_ns())
            attachment = sample.attachment
            if attachment is None:
                continue   # rmw_zenoh drops samples without an attachment
            data = sample.payload.to_bytes()
            info = _info(attachment.to_bytes(), received)
            return (data if self.raw else self._deserializer()(data)), info

    def execute(self) -> None:
        """Deliver the oldest sample (one callback, as rclpy's spin_once promises)."""
        self.execute_many(1, None)

    def execute_many(self, limit: int, stop: Callable[[], bool] | None) -> None:
        """Deliver up to `limit` buffered samples, stopping early once `stop()` holds; what
        is left goes back in the queue behind other work. spin() and
        spin_until_future_complete() use this so a burst is not paid for per sample in
        executor overhead. Typed callbacks never see MessageInfo, so it is only built for
        raw ones."""
        buffer, callback = self._buffer, self.callback
        popleft, perf_counter = buffer.popleft, time.perf_counter
        # a batch also ends after _BATCH_TIME, so slow callbacks can't starve timers
        deadline = perf_counter() + _BATCH_TIME if limit > 1 else 0.0
        try:
            if self.raw:
                for i in range(limit):
                    if i & 7 == 7 and perf_counter() > deadline:
                        break
                    try:
                        sample, received = popleft()
                    except IndexError:
                        break  # KEEP_LAST dropped it, or take() got there first
                    if self._destroyed:
                        break
                    attachment = sample.attachment
                    if attachment is None:
                        continue   # rmw_zenoh drops samples without an attachment
                    callback(sample.payload.to_bytes(), _info(attachment.to_bytes(), received))
                    if stop is not None and stop():
                        break
                return
            # typed: the hot loop of a busy subscriber, kept to the bare minimum per sample
            des = self._deserialize or self._deserializer()
            for i in range(limit):
                if i & 7 == 7 and perf_counter() > deadline:
                    break
                try:
                    sample = popleft()
                except IndexError:
                    break
                if self._destroyed:
                    break
                if sample.attachment is None:
                    continue
                callback(des(sample.payload.to_bytes()))
                if stop is not None and stop():
                    break
        finally:
            self._reschedule()

    def destroy(self) -> None:
        self._destroyed = True
        self._buffer.clear()
        self._ep._undeclare(self._sub)   # closes the channel, which ends the pump thread
        self._sub = None
        if self._pump_thread is not threading.current_thread():
            # a pump still inside zenoh when the interpreter finalises aborts the process
            self._pump_thread.join(timeout=1.0)

    def get_publisher_count(self) -> int:
        from ros2lite.graph import count
        return count(self._ep.node.context.graph.entities(), self.topic_name,
                     EntityKind.PUBLISHER)


class _SubscriptionEndpoint(Endpoint):
    kind = EntityKind.SUBSCRIPTION
