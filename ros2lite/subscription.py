"""Subscriptions: samples are buffered per subscription and delivered by an executor."""

from __future__ import annotations

import enum
import inspect
import time
from collections import deque
from collections.abc import Callable
from typing import TYPE_CHECKING, Any, Generic, cast

from ros2lite.bad_samples import BadSamples, gid_of
from ros2lite.delivery import BATCH, BATCH_TIME, deliver, deliver_with_info
from ros2lite.endpoint import Endpoint, EndpointOwner
from ros2lite.executable import Executable
from ros2lite.message_info import MessageInfo
from ros2lite.qos import HistoryPolicy, QoSProfile
from ros2lite.transport.attachment import unpack_attachment
from ros2lite.transport.keys import EntityKind
from ros2lite.type_support import MsgT

if TYPE_CHECKING:
    from ros2lite.callback_groups import CallbackGroup
    from ros2lite.executable import EntityNode
    from ros2lite.task import Task
    from ros2lite.transport.handles import Sample
    from ros2lite.transport.pull import PulledSamples
    from ros2lite.transport.session import SampleReceiver


class CallbackType(enum.Enum):
    """What a subscription callback takes: the message, or the message and its info."""

    MessageOnly = 0
    WithMessageInfo = 1


def callback_type(callback: Callable[..., object]) -> CallbackType:
    """Tell `callback(msg)` from `callback(msg, info)`, as rclpy does (RuntimeError for
    anything else)."""
    try:
        signature = inspect.signature(callback)
    except (TypeError, ValueError):  # a builtin without a signature: assume the message only
        return CallbackType.MessageOnly
    for args, kind in (((0,), CallbackType.MessageOnly), ((0, 0), CallbackType.WithMessageInfo)):
        try:
            signature.bind(*args)
        except TypeError:
            continue
        return kind
    raise RuntimeError(
        'a subscription callback must take one parameter (msg) or two (msg, msg_info)'
    )


def _info(attachment: bytes, received: int) -> MessageInfo:
    fields = unpack_attachment(attachment)
    if fields is None:
        return MessageInfo(0, received, 0, b'')
    seq, stamp, gid = fields
    return MessageInfo(stamp, received, seq, gid)


SubscriptionCallback = (
    Callable[[MsgT], object]
    | Callable[[MsgT, MessageInfo], object]
    | Callable[[bytes, MessageInfo], object]
)
"""`callback(msg)` or `callback(msg, info)` (told apart by the signature, as rclpy does), and
with raw=True the message is its CDR bytes; `async def` ones too."""


class Subscription(EndpointOwner, Executable, Generic[MsgT]):
    """Calls `callback(msg)` or `callback(msg, MessageInfo)` (told apart by its signature);
    with raw=True the message is its CDR bytes."""

    CallbackType = CallbackType

    def __init__(
        self,
        node: EntityNode,
        msg_type: type[MsgT] | str,
        topic: str,
        callback: SubscriptionCallback[MsgT],
        qos: QoSProfile | int,
        *,
        raw: bool = False,
        callback_group: CallbackGroup | None = None,
    ) -> None:
        from ros2lite.transport.pull import PulledSamples
        from ros2lite.transport.session import SampleReceiver

        Executable.__init__(self, node, callback_group)
        self._ep = _SubscriptionEndpoint(node, msg_type, topic, qos)
        ep = self._ep
        self.callback = callback
        self._callback_type = callback_type(callback)
        self._with_info = self._callback_type == CallbackType.WithMessageInfo
        self.raw = raw
        self._async = inspect.iscoroutinefunction(callback)
        keep_all = ep.qos.history == HistoryPolicy.KEEP_ALL
        # zenoh samples as a pump thread moved them: `(sample, arrival ns)` for raw ones
        # (tools like `topic hz` need arrival times), `sample` for typed ones fed by a
        # subclass hook; other typed subscriptions pull from Zenoh on the executor thread
        # (`_source` below). Bytes are copied out on the executor thread.
        self._buffer: deque[Any] = deque(maxlen=None if keep_all else max(ep.qos.depth, 1))
        self._deserialize: Callable[[bytes], MsgT] | None = None
        self._destroyed = False
        # undecodable samples so far (None until the first one)
        self.bad_samples: BadSamples | None = None
        # a subclass hook (e.g. topic monitors) sees every sample instead of the buffer
        hook = None if type(self)._on_sample is Subscription._on_sample else self._on_sample
        # typed subscriptions: the executor pulls samples itself (ros2lite.transport.pull)
        self._source: PulledSamples | None = None
        self._receiver: SampleReceiver | PulledSamples
        if raw or hook is not None:
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
        else:
            self._receiver = self._source = PulledSamples(
                node.context.require(), ep.key, ep.qos, self._notify, name=ep.topic_name
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
        if self._destroyed:
            return False
        return self._source.ready if self._source is not None else bool(self._buffer)

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
        if self._source is not None:
            return self._take_typed(self._source)
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
            if self.raw:
                return data, info
            try:
                return self._deserializer()(data), info
            except ValueError as e:  # a CdrError (imported lazily: tools stay light)
                self._bad_sample(data, info.publisher_gid, e)  # dropped: take the next one

    def _info(self, attachment: bytes, received: int) -> MessageInfo:
        return _info(attachment, received)

    def _take_typed(self, source: PulledSamples) -> tuple[MsgT, MessageInfo] | None:
        while True:
            taken = source.take(1)
            if not taken:
                return None
            sample = taken[0]
            data = sample.payload.to_bytes()
            info = _info(sample.attachment.to_bytes(), time.time_ns())  # type: ignore[union-attr]
            try:
                return self._deserializer()(data), info
            except ValueError as e:  # a CdrError: dropped, take the next one
                self._bad_sample(data, info.publisher_gid, e)

    def _execute(self, batch: bool, stop: Callable[[], bool] | None) -> Task | None:
        """Deliver the oldest sample, or in spin()/spin_until_future_complete() a batch of
        them (stopping early once `stop()` holds), so a burst is not paid for per sample in
        executor overhead; what is left goes back in the queue behind other work."""
        if self._async:
            entry = self.take()
            return (
                None
                if entry is None
                else self._call(self.callback, *(entry if self._with_info else entry[:1]))
            )
        source = self._source
        if source is not None and not (self.raw or self._with_info):
            # the hot path (ros2lite.delivery), straight from here: spin_once pays per call
            deliver(
                self,
                source,
                self._deserialize or self._deserializer(),
                BATCH if batch else 1,
                stop,
            )
        else:
            self._deliver_batch(BATCH if batch else 1, stop)
        return None

    def _deliver_batch(self, limit: int, stop: Callable[[], bool] | None) -> None:
        """MessageInfo is only built for callbacks that take it."""
        # (msg) for the hot typed loop; the others go through _deliver_with_info
        callback: Callable[..., object] = self.callback
        buffer = self._buffer
        popleft, perf_counter = buffer.popleft, time.perf_counter
        # a batch also ends after BATCH_TIME, so slow callbacks can't starve timers
        deadline = perf_counter() + BATCH_TIME if limit > 1 else 0.0
        if self.raw or self._with_info:
            self._deliver_with_info(limit, stop, deadline)
            return
        des = self._deserialize or self._deserializer()
        # (typed and pulled from Zenoh without info: _execute hands those to delivery)
        # typed, fed by a hook of a subclass: a sample that does not decode raises out of
        # the loop; the handler (free until something raises) tells a bad sample, which is
        # dropped, from the callback's own error
        first = 0
        while True:
            try:
                for i in range(first, limit):
                    if i & 7 == 7 and perf_counter() > deadline:
                        return
                    try:
                        sample = popleft()
                    except IndexError:
                        return
                    if self._destroyed:
                        return
                    if sample.attachment is None:
                        continue
                    callback(des(sample.payload.to_bytes()))
                    if stop is not None and stop():
                        return
                return
            except ValueError as e:  # a CdrError (imported lazily: tools stay light)?
                data = sample.payload.to_bytes()
                try:
                    des(data)
                except ValueError:
                    self._bad_sample(data, gid_of(sample.attachment.to_bytes()), e)
                else:
                    raise  # it decodes: the error is the callback's
                first = i + 1

    def _bad_sample(self, data: bytes, gid: bytes, error: Exception) -> None:
        """A sample that is not the topic's type: dropped, counted, reported (rate-limited)."""
        bad = self.bad_samples
        if bad is None:
            node = self._ep.node
            bad = self.bad_samples = BadSamples(
                self._ep.topic_name, self._ep.type_name, node.get_logger().warn
            )
        bad.add(gid, error, len(data))

    def _deliver_with_info(
        self, limit: int, stop: Callable[[], bool] | None, deadline: float
    ) -> None:
        """Raw bytes and/or MessageInfo: the slower loop (raw samples carry their arrival
        time; typed ones are stamped when taken). A typed sample that does not decode is
        dropped and reported, as in the hot loop."""
        if self._source is not None:  # typed, pulled from Zenoh (ros2lite.delivery)
            deliver_with_info(
                self, self._source, self._deserialize or self._deserializer(), limit, stop, deadline
            )
            return
        popleft, perf_counter = self._buffer.popleft, time.perf_counter
        callback: Callable[..., object] = self.callback
        des = None if self.raw else (self._deserialize or self._deserializer())
        for i in range(limit):
            if i & 7 == 7 and perf_counter() > deadline:
                break
            try:
                entry = popleft()
            except IndexError:
                break  # KEEP_LAST dropped it, or take() got there first
            if self._destroyed:
                break
            sample, received = entry if self.raw else (entry, time.time_ns())
            attachment = sample.attachment
            if attachment is None:
                continue  # rmw_zenoh drops samples without an attachment
            data = sample.payload.to_bytes()
            if des is None:
                message: object = data
            else:
                try:
                    message = des(data)
                except ValueError as e:  # a CdrError (imported lazily: tools stay light)
                    self._bad_sample(data, gid_of(attachment.to_bytes()), e)
                    continue
            if self._with_info:
                callback(message, _info(attachment.to_bytes(), received))
            else:
                callback(message)
            if stop is not None and stop():
                break

    def destroy(self) -> None:
        """Stop receiving: buffered samples are dropped and the token withdrawn."""
        self._destroy_event_handlers()
        self._destroyed = True
        self._buffer.clear()
        if self._source is not None:
            self._source.clear()
        self._ep._undeclare(self._receiver)  # ends the receive thread too

    def get_publisher_count(self) -> int:
        """How many publishers on the graph match this topic name."""
        from ros2lite.graph import count

        return count(self._ep.node.context.graph.entities(), self.topic_name, EntityKind.PUBLISHER)


class _SubscriptionEndpoint(Endpoint):
    kind = EntityKind.SUBSCRIPTION
