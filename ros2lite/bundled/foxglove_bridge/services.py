"""Services: every visible service of the graph offered to the clients, a client's call
made through a client of ours with a deadline (CDR or JSON)."""

from __future__ import annotations

import json
import re
from typing import TYPE_CHECKING, Any

import foxglove
from foxglove.websocket import ServiceRequest

from ros2lite.bundled.foxglove_bridge.channels import visible
from ros2lite.bundled.foxglove_bridge.state import BridgeState
from ros2lite.graph import EntityKind

if TYPE_CHECKING:
    from ros2lite.client import Client as RosClient
    from ros2lite.graph import Entity


class GraphServices:
    """The graph's services, as the clients see them."""

    def __init__(self, state: BridgeState, patterns: list[re.Pattern[str]]) -> None:
        self.state = state
        self.patterns = patterns
        self.advertised: dict[str, str] = {}  # name -> type, as advertised
        self.clients: dict[str, RosClient[Any, Any]] = {}

    def refresh(self, entities: list[Entity]) -> None:
        """Offer the graph's visible services, withdraw the ones gone."""
        from ros2lite.interfaces import definition_text
        from ros2lite.remote_types import ensure_type

        state = self.state
        server = state.server
        assert server is not None
        services: dict[str, str] = {}
        for e in entities:
            name, type_name = e.topic_name, e.type_name
            if e.kind is not EntityKind.SERVICE or not name or not type_name:
                continue
            if visible(state, name, self.patterns):
                services.setdefault(name, type_name)
        gone = [n for n, t in self.advertised.items() if services.get(n) != t]
        if gone:
            server.remove_services(gone)
            for name in gone:
                del self.advertised[name]
                client = self.clients.pop(name, None)
                if client is not None:
                    state.node.destroy_client(client)
        added = []
        for name, type_name in sorted(services.items()):
            if name in self.advertised or type_name in state.unknown_types:
                continue
            try:
                ensure_type(lambda: state.node, entities, type_name, name)
                request = definition_text(f'{type_name}_Request')
                response = definition_text(f'{type_name}_Response')
            except Exception as e:
                state.unknown_types.add(type_name)
                state.warn(f"Service '{name}': type {type_name} is unknown here ({e}); not shown")
                continue
            schema = foxglove.ServiceSchema(
                type_name,
                request=_message_schema(f'{type_name}_Request', request),
                response=_message_schema(f'{type_name}_Response', response),
            )
            added.append(foxglove.Service(name, schema=schema, handler=self.call))
            self.advertised[name] = type_name
        if added:
            server.add_services(added)

    def call(self, request: ServiceRequest) -> bytes:
        """A client's call of a graph service, answered with the response's CDR bytes (or an
        error the SDK sends back as a failed call)."""
        from ros2lite.interfaces import get_interface, serialize, set_message_fields
        from ros2lite.interfaces.cdr import service_codecs

        name = request.service_name
        type_name = self.advertised.get(name)
        if type_name is None:
            raise ValueError(f"service '{name}' is gone")
        srv = get_interface(type_name)
        if request.encoding == 'json':
            fields = json.loads(request.payload or b'{}')
            if not isinstance(fields, dict):
                raise ValueError('a JSON request is an object')
            msg = srv.Request()
            set_message_fields(msg, fields)
        else:
            msg = service_codecs(type_name)[0].deserialize(request.payload)
        client = self.clients.get(name)
        if client is None:
            client = self.state.node.create_client(srv, name, fail_without_server=True)
            self.clients[name] = client
        response = client.call(msg, timeout_sec=self.state.settings.service_timeout)
        if response is None:
            raise TimeoutError(f"service '{name}' did not answer in time")
        if request.encoding == 'json':
            from ros2lite.interfaces import message_to_dict

            return json.dumps(message_to_dict(response)).encode()
        return serialize(response)


def _message_schema(name: str, text: str) -> foxglove.MessageSchema:
    return foxglove.MessageSchema(
        encoding='cdr', schema=foxglove.Schema(name=name, encoding='ros2msg', data=text.encode())
    )
