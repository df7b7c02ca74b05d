"""Subscriptions: samples are buffered per subscription and delivered by an executor."""

from __future__ import annotations

import time
from collections import deque
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from ros2lite.endpoint import Endpoint, is_transient_local
from ros2lite.transport.keys import EntityKind
from ros2lite.transport.qos import HistoryPolicy, QoSProfile, ReliabilityPolicy


@dataclass(frozen=True)
class MessageInfo:
    """Delivery metadata from the rmw_zenoh attachment, plus our receive time."""

    source_timestamp: int           # ns since the epoch, from the publisher
    received_timestamp: int         # ns since the epoch, when the sample arrived here
    publication_sequence_number: int
    publisher_gid: bytes


def _info(attachment: bytes, received: int) -> MessageInfo:
    from ros2lite.transport.attachment import decode_attachment
    try:
        a = decode_attachment(attachment)
    except ValueError:
        return MessageInfo(0, received, 0, b'')
    return MessageInfo(a.source_timestamp, received, a.sequence_number, a.source_gid)


class Subscription:
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
        self._buffer: deque[tuple[bytes, bytes, int]] = deque(
            maxlen=None if keep_all else max(ep.qos.depth, 1))
        handler = zenoh.handlers.Callback(self._on_sample)
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
        ep._announce()

    @property
    def topic_name(self) -> str:
        return self._ep.topic_name

    @property
    def msg_type(self) -> Any:
        return self._ep.msg_class

    @property
    def qos_profile(self) -> QoSProfile:
        return self._ep.qos

    def _on_sample(self, sample: Any) -> None:
        """Zenoh thread: keep the bytes and hand the work to the executor."""
        attachment = sample.attachment
        if attachment is None:
            return  # rmw_zenoh drops samples without an attachment
        self._buffer.append((sample.payload.to_bytes(), attachment.to_bytes(), time.time_ns()))
        self._work.put(self)

    def take(self) -> tuple[Any, MessageInfo] | None:
        """The oldest buffered sample as (message or bytes, info), or None."""
        try:
            data, attachment, received = self._buffer.popleft()
        except IndexError:
            return None
        if self.raw:
            return data, _info(attachment, received)
        des = self._deserialize
        if des is None:
            from ros2lite.interfaces.cdr import codec
            from ros2lite.interfaces.registry import default_registry
            des = self._deserialize = codec(self._ep.type_name, default_registry()).deserialize
        return des(data), _info(attachment, received)

    def execute(self) -> None:
        item = self.take()
        if item is None:
            return
        if self.raw:
            self.callback(item[0], item[1])
        else:
            self.callback(item[0])

    def destroy(self) -> None:
        self._ep._undeclare(self._sub)
        self._sub = None

    def get_publisher_count(self) -> int:
        from ros2lite.graph import count
        return count(self._ep.node.context.graph.entities(), self.topic_name,
                     EntityKind.PUBLISHER)


class _SubscriptionEndpoint(Endpoint):
    kind = EntityKind.SUBSCRIPTION
