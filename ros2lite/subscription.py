"""Subscriptions: samples are buffered per subscription and delivered by an executor."""

from __future__ import annotations

import enum
import inspect
import threading
import time
from collections import deque
from collections.abc import Callable
from typing import TYPE_CHECKING, Generic, cast

from ros2lite.message_info import MessageInfo
from ros2lite.qos import HistoryPolicy, QoSProfile
from ros2lite.runtime.bad_samples import BadSamples, gid_of
from ros2lite.runtime.delivery import BATCH, BATCH_TIME, deliver, deliver_with_info
from ros2lite.runtime.endpoint import Endpoint, EndpointOwner
from ros2lite.runtime.executable import Executable
from ros2lite.transport.attachment import unpack_attachment
from ros2lite.transport.handles import Receiving
from ros2lite.transport.keys import EntityKind
from ros2lite.type_support import MsgT

if TYPE_CHECKING:
    from ros2lite.callback_groups import CallbackGroup
    from ros2lite.runtime.executable import EntityNode
    from ros2lite.task import Task
    from ros2lite.transport.handles import Sample
    from ros2lite.transport.pull import PulledSamples
    from ros2lite.transport.session import SampleReceiver

__all__ = ['CallbackType', 'Receiving', 'Subscription', 'SubscriptionCallback', 'callback_type']

# makes the one BadSamples of a subscription that two threads may find a bad sample for at once
_first_bad = threading.Lock()


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
    | Callable[[bytes], object]
    | Callable[[bytes, MessageInfo], object]
)
"""`callback(msg)` or `callback(msg, info)` (told apart by the signature, as rclpy does), and
with raw=True the message is its CDR bytes; `async def` ones too."""


class Subscription(EndpointOwner, Executable, Generic[MsgT]):
    """Calls `callback(msg)` or `callback(msg, MessageInfo)` (told apart by its signature);
    with raw=True the message is its CDR bytes.

    How samples arrive is a named strategy (:class:`Receiving`): typed subscriptions pull
    them on the executor thread, raw ones get them queued by a pump thread, and a tool that
    must see every sample at arrival gives `on_arrival(sample)`, which then runs on the
    receive thread instead of any queueing (it may call :meth:`_keep` to queue the sample)."""

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
        on_arrival: Callable[[Sample], None] | None = None,
    ) -> None:
        from ros2lite.transport.pull import PulledSamples
        from ros2lite.transport.receivers import open_receiver

        # what the executor reads first, set before the callback group or a receiver can
        # show this subscription to an executor spinning on another thread (`destroyed` is
        # read per message by runtime/delivery.py, a plain attribute; only destroy() sets it)
        self.destroyed = False
        self._source: PulledSamples | None = None
        self._buffer: deque[tuple[Sample, int]] = deque()
        Executable.__init__(self, node, callback_group)
        self._ep = _SubscriptionEndpoint(node, msg_type, topic, qos)
        ep = self._ep
        self.callback = callback
        self._callback_type = callback_type(callback)
        self._with_info = self._callback_type == CallbackType.WithMessageInfo
        self.raw = raw
        self._async = inspect.iscoroutinefunction(callback)
        keep_all = ep.qos.history == HistoryPolicy.KEEP_ALL
        # raw samples as a pump thread (or an arrival hook, through _keep) queued them,
        # `(sample, arrival ns)` (tools like `topic hz` need arrival times); typed
        # subscriptions pull from Zenoh on the executor thread (`_source` below)
        self._buffer = deque(maxlen=None if keep_all else max(ep.qos.depth, 1))
        self._deserialize: Callable[[bytes], MsgT] | None = None
        # undecodable samples so far (None until the first one)
        self.bad_samples: BadSamples | None = None
        # how samples arrive: an arrival hook (topic monitors, a waiter for one message)
        # sees every sample instead of the buffer; else raw bytes are queued, typed ones
        # pulled by the executor itself (ros2lite.transport.pull)
        self.receiving = (
            Receiving.ARRIVAL_HOOK
            if on_arrival is not None
            else Receiving.RAW_QUEUE
            if raw
            else Receiving.TYPED_PULL
        )
        receiver = open_receiver(
            self.receiving,
            node.context.require(),
            ep.key,
            ep.qos,
            self._notify,
            buffer=self._buffer if self.receiving is Receiving.RAW_QUEUE else None,
            hook=on_arrival,
            name=ep.topic_name,
            keeper=self._keep_channel,
            on_unattached=self._unattached,
        )
        self._receiver: SampleReceiver | PulledSamples = receiver
        # typed pull: the executor takes samples from here (None for the other two)
        self._source = receiver if isinstance(receiver, PulledSamples) else None
        if self._source is not None and self._source.ready:
            self._notify()  # samples came while it was being built: the executor looked away
        ep.announce()

    def _keep(self, sample: Sample) -> None:
        """Receive thread (an arrival hook passing a sample on): queue it with its arrival
        time, as a raw queue does, and make sure the executor will come for it. Samples
        without an attachment, which rmw_zenoh ignores, are dropped when taken."""
        if self.destroyed:
            return
        self._buffer.append((sample, time.time_ns()))
        self._notify()

    def _keep_channel(self, channel: PulledSamples) -> bool:
        """The typed source emptied its channel: may the node keep it for its executor to
        wait in (Parking.keep)?"""
        return self._node.parking.keep(self, channel)  # type: ignore[union-attr]  # has one

    def _unattached(self, count: int) -> None:
        """Any thread: `count` samples without an attachment came from a peer (not ROS
        messages, perhaps a flood): dropped, counted and reported as bad samples."""
        self._bad_samples().add_unattached(count)

    def has_work(self) -> bool:
        if self.destroyed:
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
        """The oldest sample as (message or bytes, info), or None. For typed subscriptions
        `received_timestamp` is the time of the take."""
        if self._source is not None:
            return self._take_typed(self._source)
        while True:
            try:
                sample, received = self._buffer.popleft()
            except IndexError:
                return None
            attachment = sample.attachment
            if attachment is not None:  # rmw_zenoh drops samples without one
                return sample.payload.to_bytes(), _info(attachment.to_bytes(), received)

    def _decoded(self, data: bytes, attachment: bytes) -> MsgT | None:
        """The message in `data`; None when it does not decode (dropped and reported)."""
        try:
            return self._deserializer()(data)
        except ValueError as e:  # a CdrError (imported lazily: tools stay light)
            self._bad_sample(data, gid_of(attachment), e)
            return None

    def _take_typed(self, source: PulledSamples) -> tuple[MsgT, MessageInfo] | None:
        while True:
            taken = source.take(1)
            if not taken:
                return None
            sample = taken[0]
            attachment = sample.attachment.to_bytes()  # type: ignore[union-attr]  # take() checked
            message = self._decoded(sample.payload.to_bytes(), attachment)
            if message is not None:
                return message, _info(attachment, time.time_ns())

    def run_pending(self, batch: bool, stop: Callable[[], bool] | None) -> Task | None:
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
        limit = BATCH if batch else 1
        if source is None:  # raw: the buffer a pump thread fills
            self._deliver_raw(limit, stop)
        elif self._with_info:
            # a batch also ends after BATCH_TIME, so slow callbacks can't starve timers
            deadline = time.perf_counter() + BATCH_TIME if batch else 0.0
            deliver_with_info(
                self, source, self._deserializer(), limit, stop, deadline, self._bad_sample, _info
            )
        else:  # the hot path (runtime/delivery.py), straight from here: spin_once pays per call
            decode = self._deserialize or self._deserializer()
            deliver(self, source, decode, limit, stop, self._bad_sample)
        return None

    def _bad_sample(self, data: bytes, gid: bytes, error: Exception) -> None:
        """A sample that is not the topic's type: dropped, counted, reported (rate-limited)."""
        self._bad_samples().add(gid, error, len(data))

    def _bad_samples(self) -> BadSamples:
        bad = self.bad_samples
        if bad is None:
            with _first_bad:  # (the doorbell and the executor thread may both find one)
                bad = self.bad_samples
                if bad is None:
                    warn = self._ep.node.get_logger().warn
                    bad = self.bad_samples = BadSamples(
                        self._ep.topic_name, self._ep.type_name, warn
                    )
        return bad

    def _deliver_raw(self, limit: int, stop: Callable[[], bool] | None) -> None:
        """Raw bytes, with MessageInfo for callbacks that take it (stamped at arrival); a
        batch also ends after BATCH_TIME, so slow callbacks can't starve timers."""
        popleft, perf_counter = self._buffer.popleft, time.perf_counter
        deadline = perf_counter() + BATCH_TIME if limit > 1 else 0.0
        callback: Callable[..., object] = self.callback
        for i in range(limit):
            if i & 7 == 7 and perf_counter() > deadline:
                break
            try:
                sample, received = popleft()
            except IndexError:
                break  # KEEP_LAST dropped it, or take() got there first
            if self.destroyed:
                break
            attachment = sample.attachment
            if attachment is None:
                continue  # rmw_zenoh drops samples without an attachment
            data = sample.payload.to_bytes()
            if self._with_info:
                callback(data, _info(attachment.to_bytes(), received))
            else:
                callback(data)
            if stop is not None and stop():
                break

    def destroy(self) -> None:
        """Stop receiving: buffered samples are dropped and the token withdrawn."""
        self._destroy_event_handlers()
        self.destroyed = True
        self._buffer.clear()
        if self._source is not None:
            self._source.clear()
            self._node.parking.unkeep(self)  # type: ignore[union-attr]  # subscriptions have one
        self._ep.undeclare(self._receiver)  # ends the receive thread too

    def get_publisher_count(self) -> int:
        """How many publishers are matched: same topic name and type, any QoS (as
        rmw_zenoh's graph cache counts them)."""
        from ros2lite.graph import matched_count

        ep = self._ep
        entities = ep.node.context.graph.entities()
        return matched_count(entities, ep.topic_name, ep.type_name, EntityKind.PUBLISHER)


class _SubscriptionEndpoint(Endpoint):
    kind = EntityKind.SUBSCRIPTION
