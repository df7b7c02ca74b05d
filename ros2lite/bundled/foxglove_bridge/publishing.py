"""Client publishing: a channel a client advertises becomes a publisher in the graph, its
messages published as they come (CDR as is, JSON filled into a message)."""

from __future__ import annotations

import json
import re
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from foxglove.websocket import ClientChannel

from ros2lite.bundled.foxglove_bridge.state import BridgeState, matches

if TYPE_CHECKING:
    from ros2lite.publisher import Publisher

CLIENT_ENCODINGS = ('cdr', 'json')
# channels one client may advertise (each is a publisher in the graph)
_CLIENT_CHANNEL_LIMIT = 1000


def _type_name(schema_name: str) -> str:
    """'pkg/msg/Type' from what a client names ('pkg/Type' too)."""
    parts = schema_name.split('/')
    return f'{parts[0]}/msg/{parts[1]}' if len(parts) == 2 else schema_name


@dataclass
class _ClientPublication:
    """A channel a client advertised, and the publisher that carries its messages."""

    topic: str
    type_name: str
    encoding: str
    publisher: Publisher[Any] | None = None
    msg_class: Any = None


class ClientPublishing:
    """The channels clients advertise, each with its publisher."""

    def __init__(self, state: BridgeState, patterns: list[re.Pattern[str]]) -> None:
        self.state = state
        self.patterns = patterns
        self.channels: dict[tuple[int, int], _ClientPublication] = {}

    def advertise(self, client_id: int, channel: ClientChannel) -> None:
        from ros2lite.interfaces import get_interface

        key = (client_id, channel.id)
        if channel.encoding not in CLIENT_ENCODINGS:
            self.state.status(f'Unsupported encoding {channel.encoding!r} for {channel.topic}')
            return
        if not matches(self.patterns, channel.topic):
            self.state.status(f"Topic '{channel.topic}' is not whitelisted for client publishing")
            return
        if sum(1 for c, _ in self.channels if c == client_id) >= _CLIENT_CHANNEL_LIMIT:
            self.state.status(f'A client may advertise {_CLIENT_CHANNEL_LIMIT} channels at most')
            return
        type_name = _type_name(channel.schema_name)
        try:
            msg_class = get_interface(type_name)
            publisher = self.state.node.create_publisher(msg_class, channel.topic, 10)
        except Exception as e:
            self.state.status(f"Cannot advertise '{channel.topic}' ({channel.schema_name}): {e}")
            return
        self.channels[key] = _ClientPublication(
            channel.topic, type_name, channel.encoding, publisher, msg_class
        )

    def publish(self, client_id: int, channel_id: int, data: bytes) -> None:
        pub = self.channels.get((client_id, channel_id))
        if pub is None or pub.publisher is None:
            return  # the SDK refuses unknown channel ids; one we could not advertise
        try:
            if pub.encoding == 'cdr':
                pub.publisher.publish(data)
                return
            from ros2lite.interfaces import set_message_fields

            fields = json.loads(data)
            if not isinstance(fields, dict):
                raise ValueError('a JSON message is an object')
            msg = pub.msg_class()
            set_message_fields(msg, fields)
            pub.publisher.publish(msg)
        except Exception as e:
            self.state.status(f"Dropped a message to '{pub.topic}': {e}")

    def unadvertise(self, client_id: int, channel_id: int) -> None:
        """A client's channel withdrawn: its publisher goes."""
        pub = self.channels.pop((client_id, channel_id), None)
        if pub is not None and pub.publisher is not None:
            self.state.node.destroy_publisher(pub.publisher)
