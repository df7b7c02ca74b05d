"""Publishers: CDR payload plus the 33-byte attachment, on the rmw_zenoh data key."""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import TYPE_CHECKING, Generic

from ros2lite.exceptions import InvalidHandle
from ros2lite.qos import QoSProfile
from ros2lite.runtime.endpoint import Endpoint, EndpointOwner
from ros2lite.transport.attachment import GID_SIZE, PACK_CURRENT
from ros2lite.transport.keys import EntityKind
from ros2lite.type_support import Msg, MsgT

# per-message calls of publish(), bound once
_pack = PACK_CURRENT
_now = time.time_ns

if TYPE_CHECKING:
    from ros2lite.duration import Duration
    from ros2lite.runtime.executable import EntityNode
    from ros2lite.transport.session import Publisher as ZenohPublisher


class Publisher(EndpointOwner, Generic[MsgT]):
    """Publishes messages (or ready CDR bytes) with rmw_zenoh's sequence/timestamp/GID."""

    def __init__(
        self, node: EntityNode, msg_type: type[MsgT] | str, topic: str, qos: QoSProfile | int
    ) -> None:
        from ros2lite.transport.session import declare_publisher

        self._ep = _PublisherEndpoint(node, msg_type, topic, qos)
        ep = self._ep
        self._pub: ZenohPublisher | None = declare_publisher(node.context.require(), ep.key, ep.qos)
        ep.announce()
        self._gid = ep.gid
        self._seq = 0
        self._serialize: Callable[[Msg], bytes] | None = None
        self._msg_class = ep.msg_class
        self._put: Callable[..., object] = self._pub.put

    @property
    def sent(self) -> int:
        """Messages published so far (rmw_zenoh's sequence number of the last one)."""
        return self._seq

    @property
    def gid(self) -> bytes:
        """The 16-byte global id rmw_zenoh puts in every sample's attachment."""
        return self._gid

    def publish(self, msg: MsgT | bytes | bytearray | memoryview) -> None:
        """Send a message object, or bytes that already hold its CDR encoding."""
        # hot path first: a message of exactly our class, through its cached codec
        if type(msg) is self._msg_class:
            ser = self._serialize
            if ser is None:
                ser = self._serialize = self._codec_serializer()
            try:
                data = ser(msg)  # type: ignore[arg-type]  # exactly our message class
            except Exception as e:  # the raw generated function: name the type here
                from ros2lite.interfaces.errors import CdrError

                raise CdrError(f'cannot serialize {self._ep.type_name}: {e}') from None
        elif isinstance(msg, (bytes, bytearray, memoryview)):
            data = bytes(msg)
        else:
            if getattr(msg, '_TYPE_NAME', None) != self._ep.type_name:
                raise TypeError(f"publisher of '{self._ep.type_name}' got {type(msg).__name__}")
            from ros2lite.interfaces import serialize

            data = serialize(msg)
        self._seq = seq = self._seq + 1
        self._put(data, attachment=_pack(seq, _now(), GID_SIZE, self._gid))

    def _codec_serializer(self) -> Callable[[Msg], bytes]:
        from ros2lite.interfaces.cdr import codec

        return codec(self._ep.type_name).raw_serializer()

    def wait_for_all_acked(self, timeout: Duration | None = None) -> bool:
        """rclpy's wait for every subscription to acknowledge what was published. Zenoh has no
        per-message acknowledgements (a reliable link delivers or fails), so, like
        rmw_zenoh_cpp, there is nothing to wait for: True."""
        if self._pub is None:
            _destroyed()
        return True

    def assert_liveliness(self) -> None:
        """Liveliness is the endpoint's token, kept alive by the session (rmw_zenoh's way):
        nothing to assert by hand."""

    def get_subscription_count(self) -> int:
        """How many subscriptions are matched: same topic name and type, any QoS (as
        rmw_zenoh's graph cache counts them)."""
        from ros2lite.graph import matched_count

        ep = self._ep
        entities = ep.node.context.graph.entities()
        return matched_count(entities, ep.topic_name, ep.type_name, EntityKind.SUBSCRIPTION)

    def destroy(self) -> None:
        """Withdraw the publisher and its token; publishing afterwards raises."""
        self._destroy_event_handlers()
        self._ep.undeclare(self._pub)
        self._pub = None
        self._put = _destroyed


def _destroyed(*_: object, **__: object) -> None:

    raise InvalidHandle('publisher has been destroyed')


class _PublisherEndpoint(Endpoint):
    kind = EntityKind.PUBLISHER
