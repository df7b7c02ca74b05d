"""What publishers and subscriptions share: type resolution, keys, tokens and QoS mapping."""

from __future__ import annotations

from typing import TYPE_CHECKING

from ros2lite.qos import QoSProfile
from ros2lite.transport.keys import EntityKind, endpoint_token, topic_key

if TYPE_CHECKING:
    from collections.abc import Sequence

    from ros2lite.runtime.executable import Destroyable, EntityNode
    from ros2lite.transport.handles import Handle


def resolve_type(msg_type: type | str) -> tuple[str, type]:
    """(type name, class) from a message or service class or a 'pkg/msg/Name' string."""
    from ros2lite.interfaces import get_interface
    from ros2lite.interfaces.registry import normalize_name

    if isinstance(msg_type, str):
        name = normalize_name(msg_type)
        return name, get_interface(name)
    name = str(getattr(msg_type, '_TYPE_NAME', '') or '')
    if not name:
        raise TypeError(f'not a ros2lite message type: {msg_type!r}')
    return name, msg_type


def as_qos(qos: QoSProfile | int) -> QoSProfile:
    """rclpy accepts a depth wherever a profile goes."""
    if isinstance(qos, QoSProfile):
        return qos
    if isinstance(qos, int) and not isinstance(qos, bool):
        return QoSProfile(depth=qos)
    raise TypeError(f'Expected QoSProfile or int, but received {type(qos)!r}')


class EndpointOwner:
    """What publishers and subscriptions expose about their endpoint (`self._ep`)."""

    _ep: Endpoint
    # QoS event handlers (ros2lite.event_handler), set by the node that made the endpoint
    # (rclpy's attribute)
    event_handlers: Sequence[Destroyable] = []

    def _destroy_event_handlers(self) -> None:
        handlers, self.event_handlers = self.event_handlers, []
        for handler in handlers:
            handler.destroy()

    @property
    def endpoint(self) -> Endpoint:
        """The graph endpoint it announces (names, type, QoS, node, kind)."""
        return self._ep

    @property
    def topic_name(self) -> str:
        """The fully resolved topic (or service) name."""
        return self._ep.topic_name

    @property
    def msg_type(self) -> type:
        """The message class (or the stand-in of a type known only by name and hash)."""
        return self._ep.msg_class

    @property
    def qos_profile(self) -> QoSProfile:
        """The QoS this endpoint was created with (a depth becomes a KEEP_LAST profile)."""
        return self._ep.qos

    def destroy(self) -> None:
        """Undeclare the Zenoh entity and the liveliness token."""
        raise NotImplementedError


class Endpoint:
    """A topic endpoint of a node, announced by a liveliness token while it lives."""

    kind: EntityKind

    def __init__(
        self, node: EntityNode, msg_type: type | str, topic: str, qos: QoSProfile | int
    ) -> None:
        from ros2lite.interfaces import type_hash

        self.node = node
        self.type_name, self.msg_class = resolve_type(msg_type)
        # a type known only by name and hash (no local definition: `bag play` of a bag's own
        # types, `bag record` of a remote node's) may carry its hash along
        self.type_hash = getattr(msg_type, '_TYPE_HASH', None) or type_hash(self.type_name)
        # a service's or client's name is validated as one (errors say 'service name')
        service = self.kind in (EntityKind.SERVICE, EntityKind.CLIENT)
        self.topic_name = (node.resolve_service_name if service else node.resolve_topic_name)(topic)
        self.qos = as_qos(qos)
        ctx = node.context
        self.key = topic_key(ctx.domain_id, self.topic_name, self.type_name, self.type_hash)
        self.entity_id = ctx.next_entity_id()
        self.token_key = endpoint_token(
            ctx.domain_id,
            ctx.zid,
            node.node_id,
            self.entity_id,
            self.kind,
            node.get_namespace(),
            node.get_name(),
            self.topic_name,
            self.type_name,
            self.type_hash,
            self.qos,
            ctx.enclave,
        )
        self._token: Handle | None = None

    def announce(self) -> None:
        # rmw_zenoh declares the data entity first, then the token
        from ros2lite.transport.session import declare_token

        self._token = declare_token(self.node.context.require(), self.token_key)
        # this process' graph sees its own new endpoint at once (rcl's does)
        self.node.context.graph_changed_locally(self.token_key, True)

    def undeclare(self, *entities: Handle | None) -> None:
        from ros2lite.transport.session import undeclare_quietly

        if self._token is not None:
            self.node.context.graph_changed_locally(self.token_key, False)
        undeclare_quietly(self._token, *entities)
        self._token = None

    @property
    def gid(self) -> bytes:
        """The 16-byte global id rmw_zenoh derives from the endpoint's token."""
        from ros2lite.transport.attachment import gid_from_token

        return gid_from_token(self.token_key)
