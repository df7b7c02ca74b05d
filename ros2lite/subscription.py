"""Subscriptions: samples are buffered per subscription and delivered by an executor."""

from __future__ import annotations

import inspect
import time
from collections import deque
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Generic, cast

from ros2lite.endpoint import Endpoint, EndpointOwner
from ros2lite.executable import Executable
from ros2lite.qos import HistoryPolicy, QoSProfile
from ros2lite.transport.attachment import unpack_attachment
from ros2lite.transport.keys import EntityKind
from ros2lite.type_support import MsgT

if TYPE_CHECKING:
    from ros2lite.callback_groups import CallbackGroup
    from ros2lite.node import Node
    from ros2lite.task import Task
    from ros2lite.transport.handles import Sample


@dataclass(frozen=True)
class MessageInfo:
    """Delivery metadata from the rmw_zenoh attachment, plus our receive time."""

    source_timestamp: int  # ns since the epoch, from the publisher
    received_timestamp: int  # ns since the epoch, when the sample arrived here
    publication_sequence_number: int
    publisher_gid: bytes


# longest run of callbacks of one subscription in one executor turn: count and seconds
_BATCH = 512
_BATCH_TIME = 0.002


def _info(attachment: bytes, received: int) -> MessageInfo:
    fields = unpack_attachment(attachment)
    if fields is None:
        return MessageInfo(0, received, 0, b'')
    seq, stamp, gid = fields
    return MessageInfo(stamp, received, seq, gid)


SubscriptionCallback = Callable[[MsgT], object] | Callable[[bytes, MessageInfo], object]
"""`callback(msg)`, or with raw=True `callback(cdr_bytes, info)`; `async def` ones too."""


class Subscription(EndpointOwner, Executable, Generic[MsgT]):
    """Calls `callback(msg)`; with raw=True calls `callback(cdr_bytes, MessageInfo)`."""

    def __init__(
        self,
        node: Node,
        msg_type: type[MsgT] | str,
        topic: str,
        callback: SubscriptionCallback[MsgT],
        qos: QoSProfile | int,
        *,
        raw: bool = False,
        callback_group: CallbackGroup | None = None,
    ) -> None:
        from ros2lite.transport.session import SampleReceiver

        Executable.__init__(self, node, callback_group)
        self._ep = _SubscriptionEndpoint(node, msg_type, topic, qos)
        ep = self._ep
        self.callback = callback
        self.raw = raw
        self._async = inspect.iscoroutinefunction(callback)
        keep_all = ep.qos.history == HistoryPolicy.KEEP_ALL
        # zenoh samples as they came: `sample` for typed subscriptions, `(sample, arrival ns)`
        # for raw ones (tools like `topic hz` need arrival times). Bytes are copied out on the
        # executor thread, keeping the pump thread's share of the GIL small.
        self._buffer: deque[Any] = deque(maxlen=None if keep_all else max(ep.qos.depth, 1))
        self._deserialize: Callable[[bytes], MsgT] | None = None
        self._destroyed = False
        # a subclass hook (e.g. topic monitors) sees every sample instead of the buffer
        hook = None if type(self)._on_sample is Subscription._on_sample else self._on_sample
        self._receiver = SampleReceiver(
            node.context.require(),
            ep.key,
            ep.qos,
            self._buffer,
            self._notify,
            stamp=raw,
            hook=hook,
            name=ep.topic_name,
        )
        ep._announce()

    def _on_sample(self, sample: Sample) -> None:
        """Receive thread: keep the sample and make sure the executor will come for it.
        Samples without an attachment, which rmw_zenoh ignores, are dropped when taken."""
        if self._destroyed:
            return
        self._buffer.append((sample, time.time_ns()) if self.raw else sample)
        self._notify()

    def _has_work(self) -> bool:
        return bool(self._buffer) and not self._destroyed

    def _deserializer(self) -> Callable[[bytes], MsgT]:
        des = self._deserialize
        if des is None:
            from ros2lite.interfaces.cdr import codec

            # the codec of this subscription's own type builds MsgT messages
            des = self._deserialize = cast(
                'Callable[[bytes], MsgT]', codec(self._ep.type_name).fast_deserializer()
            )
        return des

    def take(self) -> tuple[MsgT | bytes, MessageInfo] | None:
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
                continue  # rmw_zenoh drops samples without an attachment
            data = sample.payload.to_bytes()
            info = _info(attachment.to_bytes(), received)
            return (data if self.raw else self._deserializer()(data)), info

    def _execute(self, batch: bool, stop: Callable[[], bool] | None) -> Task | None:
        """Deliver the oldest sample, or in spin()/spin_until_future_complete() a batch of
        them (stopping early once `stop()` holds), so a burst is not paid for per sample in
        executor overhead; what is left goes back in the queue behind other work."""
        if self._async:
            entry = self.take()
            return (
                None
                if entry is None
                else self._call(self.callback, *(entry if self.raw else entry[:1]))
            )
        self._deliver_batch(_BATCH if batch else 1, stop)
        return None

    def _deliver_batch(self, limit: int, stop: Callable[[], bool] | None) -> None:
        """Typed callbacks never see MessageInfo, so it is only built for raw ones."""
        # (bytes, MessageInfo) for raw subscriptions, (msg) for typed ones
        callback: Callable[..., object] = self.callback
        buffer = self._buffer
        popleft, perf_counter = buffer.popleft, time.perf_counter
        # a batch also ends after _BATCH_TIME, so slow callbacks can't starve timers
        deadline = perf_counter() + _BATCH_TIME if limit > 1 else 0.0
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
                    continue  # rmw_zenoh drops samples without an attachment
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

    def destroy(self) -> None:
        """Stop receiving: buffered samples are dropped and the token withdrawn."""
        self._destroyed = True
        self._buffer.clear()
        self._ep._undeclare(self._receiver)  # ends the receive thread too

    def get_publisher_count(self) -> int:
        """How many publishers on the graph match this topic name."""
        from ros2lite.graph import count

        return count(self._ep.node.context.graph.entities(), self.topic_name, EntityKind.PUBLISHER)


class _SubscriptionEndpoint(Endpoint):
    kind = EntityKind.SUBSCRIPTION
