"""Publishers: CDR payload plus the 33-byte attachment, on the rmw_zenoh data key."""

from __future__ import annotations

import struct
import time
from typing import Any

from ros2lite.endpoint import Endpoint, is_transient_local, zenoh_options
from ros2lite.transport.keys import EntityKind
from ros2lite.transport.qos import QoSProfile

_ATTACHMENT_HEAD = struct.Struct('<qqB')


class Publisher:
    """Publishes messages (or ready CDR bytes) with rmw_zenoh's sequence/timestamp/GID."""

    def __init__(self, node: Any, msg_type: Any, topic: str, qos: QoSProfile | int) -> None:
        self._ep = _PublisherEndpoint(node, msg_type, topic, qos)
        ep = self._ep
        session = node.context.session
        options = zenoh_options(ep.qos)
        self._pub: Any
        if is_transient_local(ep.qos):
            import zenoh.ext
            self._pub = zenoh.ext.declare_advanced_publisher(
                session, ep.key, cache=zenoh.ext.CacheConfig(max(ep.qos.depth, 1)),
                publisher_detection=True, **options)
        else:
            self._pub = session.declare_publisher(ep.key, **options)
        ep._announce()
        self._gid = ep.gid
        self._seq = 0
        self._serialize: Any = None

    @property
    def topic_name(self) -> str:
        return self._ep.topic_name

    @property
    def msg_type(self) -> Any:
        return self._ep.msg_class

    @property
    def qos_profile(self) -> QoSProfile:
        return self._ep.qos

    @property
    def gid(self) -> bytes:
        return self._gid

    def publish(self, msg: Any) -> None:
        """Send a message object, or bytes that already hold its CDR encoding."""
        if isinstance(msg, (bytes, bytearray, memoryview)):
            data = bytes(msg)
        else:
            if type(msg) is not self._ep.msg_class and \
                    getattr(msg, '_TYPE_NAME', None) != self._ep.type_name:
                raise TypeError(f"publisher of '{self._ep.type_name}' got {type(msg).__name__}")
            ser = self._serialize
            if ser is None:
                from ros2lite.interfaces import serialize
                ser = self._serialize = serialize
            data = ser(msg)
        self._seq += 1
        self._pub.put(data, attachment=_ATTACHMENT_HEAD.pack(self._seq, time.time_ns(), 16)
                      + self._gid)

    def get_subscription_count(self) -> int:
        from ros2lite.graph import count
        return count(self._ep.node.context.graph.entities(), self.topic_name,
                     EntityKind.SUBSCRIPTION)

    def destroy(self) -> None:
        self._ep._undeclare(self._pub)
        self._pub = None


class _PublisherEndpoint(Endpoint):
    kind = EntityKind.PUBLISHER
