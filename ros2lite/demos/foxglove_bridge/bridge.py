"""The bridge: a ROS node that shows its graph to Foxglove clients through `foxglove-sdk`.

Every topic of the graph is a channel (`cdr` messages, the `ros2msg` schema with its full
dependency text, as our bags write it); a topic is subscribed in Zenoh only while some client
subscribes to its channel, and samples go from the receive thread to the SDK as CDR bytes,
never decoded. The SDK queues them per client and drops the oldest when a client falls
behind, so a slow client never pushes back on the robot.

The SDK calls the listener on its own threads. Anything that declares or undeclares
something in Zenoh (subscribing, a client's publishers, the graph's channels and services)
is handed to one worker thread, so an SDK callback never waits on Zenoh while a receive
thread waits on the SDK. Service calls and parameter requests block the SDK thread that asked,
each with a deadline, as the C++ bridge does.
"""

from __future__ import annotations

import json
import logging
import queue
import re
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import foxglove
from foxglove.websocket import (
    Capability,
    ChannelView,
    Client,
    ClientChannel,
    ServerListener,
    ServiceRequest,
    StatusLevel,
    WebSocketServer,
)

from ros2lite.demos.foxglove_bridge.parameters import RemoteParameters, split_name, to_foxglove
from ros2lite.graph import EntityKind
from ros2lite.names import is_hidden_name
from ros2lite.qos import HistoryPolicy, QoSProfile, match_publishers_qos

if TYPE_CHECKING:
    from ros2lite.client import Client as RosClient
    from ros2lite.graph import Entity
    from ros2lite.monitor.subscription import MonitoredSubscription
    from ros2lite.node import Node
    from ros2lite.publisher import Publisher
    from ros2lite.subscription import Subscription

__all__ = ['CAPABILITIES', 'Bridge', 'Settings']

Say = Callable[[str], object]

# capability names of the C++ bridge's `capabilities` parameter -> the SDK's
CAPABILITIES = {
    'clientPublish': Capability.ClientPublish,
    'parameters': Capability.Parameters,
    'parametersSubscribe': Capability.Parameters,
    'services': Capability.Services,
    'connectionGraph': Capability.ConnectionGraph,
    'time': Capability.Time,
}
DEFAULT_CAPABILITIES = [
    'clientPublish',
    'parameters',
    'parametersSubscribe',
    'services',
    'connectionGraph',
    'assets',
]
CLIENT_ENCODINGS = ('cdr', 'json')
# how often the graph is looked at when no change was heard (seconds)
_REFRESH_PERIOD = 1.0
# what the SDK logs (at INFO) when a client's queue overflowed and it dropped the oldest
_OUTBOX_FULL = re.compile(r'outbox for client (\S+) full')
# a client's queued publish data beyond this is dropped (bytes), so a flood cannot grow memory
_CLIENT_DATA_LIMIT = 64 * 1024 * 1024
# channels one client may advertise (each is a publisher in the graph)
_CLIENT_CHANNEL_LIMIT = 1000


@dataclass
class Settings:
    """The bridge's parameters, as the C++ bridge names them."""

    port: int = 8765
    address: str = '127.0.0.1'
    topic_whitelist: list[str] = field(default_factory=lambda: ['.*'])
    service_whitelist: list[str] = field(default_factory=lambda: ['.*'])
    param_whitelist: list[str] = field(default_factory=lambda: ['.*'])
    client_topic_whitelist: list[str] = field(default_factory=lambda: ['.*'])
    capabilities: list[str] = field(default_factory=lambda: list(DEFAULT_CAPABILITIES))
    message_backlog_size: int = 1024
    send_buffer_limit: int = 10_000_000
    min_qos_depth: int = 1
    max_qos_depth: int = 25
    include_hidden: bool = False
    ignore_unresponsive_param_nodes: bool = True
    service_timeout: float = 5.0
    use_sim_time: bool = False
    tls: bool = False
    certfile: str = ''
    keyfile: str = ''


def compile_patterns(patterns: list[str], what: str) -> list[re.Pattern[str]]:
    """The regexes of a whitelist; a bad one is the user's error, named."""
    out = []
    for p in patterns:
        try:
            out.append(re.compile(p))
        except re.error as e:
            raise ValueError(f"invalid regular expression '{p}' in {what}: {e}") from None
    return out


def _matches(patterns: list[re.Pattern[str]], name: str) -> bool:
    return any(p.fullmatch(name) for p in patterns)


def _type_name(schema_name: str) -> str:
    """'pkg/msg/Type' from what a client names ('pkg/Type' too)."""
    parts = schema_name.split('/')
    return f'{parts[0]}/msg/{parts[1]}' if len(parts) == 2 else schema_name


@dataclass
class _Topic:
    """One advertised (topic, type): its channel and, while clients watch, its subscription."""

    name: str
    type_name: str
    channel: foxglove.Channel
    subscribers: set[int] = field(default_factory=set)  # client ids
    subscription: MonitoredSubscription | None = None


@dataclass
class _ClientPublication:
    """A channel a client advertised, and the publisher that carries its messages."""

    topic: str
    type_name: str
    encoding: str
    publisher: Publisher[Any] | None = None
    msg_class: Any = None


class Bridge(ServerListener):
    """Serves `node`'s graph on a Foxglove WebSocket server until `close()`."""

    def __init__(
        self,
        node: Node,
        settings: Settings,
        *,
        log: Callable[[str], object] | None = None,
        warn: Callable[[str], object] | None = None,
    ) -> None:
        self.node = node
        self.settings = settings
        self._log = log or node.get_logger().info
        self._warn = warn or node.get_logger().warning
        self._topic_patterns = compile_patterns(settings.topic_whitelist, 'topic_whitelist')
        self._service_patterns = compile_patterns(settings.service_whitelist, 'service_whitelist')
        self._client_topic_patterns = compile_patterns(
            settings.client_topic_whitelist, 'client_topic_whitelist'
        )
        param_patterns = compile_patterns(settings.param_whitelist, 'param_whitelist')
        caps = set(settings.capabilities)
        unknown = caps - set(CAPABILITIES) - {'assets'}
        if unknown:
            raise ValueError(f'unknown capabilities: {", ".join(sorted(unknown))}')
        self._caps = caps
        if settings.send_buffer_limit != Settings.send_buffer_limit:
            self._warn(
                'send_buffer_limit (bytes) is not used: foxglove-sdk bounds each client\'s '
                'queue by message_backlog_size (messages)'
            )
        self._own = node.get_fully_qualified_name()
        self._context = foxglove.Context()
        self._topics: dict[tuple[str, str], _Topic] = {}
        self._by_channel: dict[int, _Topic] = {}
        self._unknown_types: set[str] = set()
        self._services: dict[str, str] = {}  # name -> type, as advertised
        self._service_clients: dict[str, RosClient[Any, Any]] = {}
        self._client_channels: dict[tuple[int, int], _ClientPublication] = {}
        self._client_bytes = 0
        self._client_bytes_lock = threading.Lock()
        self._graph_subscribed = False
        self._last_graph: object = None
        self._param_names: set[str] = set()
        self._param_lock = threading.Lock()
        self._events: queue.Queue[tuple[Any, ...]] = queue.Queue()
        # (client, channel) -> subscribed, the latest wish only: a client flipping a
        # subscription a million times leaves one entry, not a million events
        self._wishes: dict[tuple[int, int], bool] = {}
        self._wishes_lock = threading.Lock()
        self._dirty = threading.Event()
        self._stopping = threading.Event()
        self._worker: threading.Thread | None = None
        self._param_events: Subscription[Any] | None = None
        self._clock_sub: Subscription[Any] | None = None
        self.params = RemoteParameters(
            node,
            self._node_names,
            param_patterns,
            ignore_unresponsive=settings.ignore_unresponsive_param_nodes,
            warn=self._warn,
        )
        self.server: WebSocketServer | None = None

    # -- life ----------------------------------------------------------------------------------
    def start(self) -> WebSocketServer:
        """Open the server and start following the graph."""
        s = self.settings
        names = {c for c in self._caps if c in CAPABILITIES}
        if s.use_sim_time:
            names.add('time')
        # the SDK's Capability is not hashable: one per distinct value, by name
        capabilities = list({CAPABILITIES[c].name: CAPABILITIES[c] for c in names}.values())
        cert = key = None
        if s.tls:
            if not s.certfile or not s.keyfile:
                raise ValueError("tls needs both 'certfile' and 'keyfile'")
            cert, key = _read(s.certfile), _read(s.keyfile)
        # the SDK logs on its own threads, some holding its locks: no I/O there, the worker
        # writes (a blocked stderr then stalls only the worker, never the SDK)
        _follow_sdk_log(
            self.tell_clients,
            lambda m: self._events.put(('warn', m)),
            lambda m: self._events.put(('log', m)),
        )
        self.server = foxglove.start_server(
            name=self._own,
            host=s.address,
            port=s.port,
            capabilities=capabilities,
            server_listener=self,
            supported_encodings=list(CLIENT_ENCODINGS),
            context=self._context,
            message_backlog_size=max(1, s.message_backlog_size),
            tls_cert=cert,
            tls_key=key,
        )
        self.node.context.graph.add_listener(self._graph_changed)
        if 'parametersSubscribe' in self._caps:
            self._param_events = self.node.create_subscription(
                _interface('rcl_interfaces/msg/ParameterEvent'),
                '/parameter_events',
                self._on_parameter_event,
                10,
            )
        if s.use_sim_time:
            self._clock_sub = self.node.create_subscription(
                _interface('rosgraph_msgs/msg/Clock'), '/clock', self._on_clock, 10
            )
        self._refresh()
        self._worker = threading.Thread(target=self._work, name='foxglove-bridge', daemon=True)
        self._worker.start()
        scheme = 'wss' if s.tls else 'ws'
        self._log(f'Foxglove bridge listening on {scheme}://{s.address}:{self.server.port}')
        return self.server

    @property
    def port(self) -> int:
        """The port the server listens on (the chosen one when `port` was 0)."""
        assert self.server is not None
        return self.server.port

    def close(self) -> None:
        """Stop serving: the server, the worker, every subscription and publisher we made."""
        self._stopping.set()
        self.node.context.graph.remove_listener(self._graph_changed)
        if self._worker is not None:
            self._events.put(('stop',))
            self._worker.join(5.0)
        if self.server is not None:
            self.server.stop()
        for topic in list(self._topics.values()):
            self._unsubscribe_topic(topic)
            topic.channel.close()
        self._topics.clear()

    # -- the worker: everything that declares in Zenoh ----------------------------------------
    def _work(self) -> None:
        last = time.monotonic()
        while not self._stopping.is_set():
            try:
                event = self._events.get(timeout=0.1)
            except queue.Empty:
                event = None
            try:
                if event is not None:
                    if event[0] == 'stop':
                        return
                    self._handle(event)
                now = time.monotonic()
                if self._dirty.is_set() or now - last >= _REFRESH_PERIOD:
                    self._dirty.clear()
                    last = now
                    self._refresh()
            except Exception as e:  # one bad request must not end the bridge
                if self._stopping.is_set():
                    return
                self._warn(f'foxglove_bridge: {e}')

    def _handle(self, event: tuple[Any, ...]) -> None:
        kind = event[0]
        if kind == 'wishes':
            with self._wishes_lock:
                wishes, self._wishes = self._wishes, {}
            for (client_id, channel_id), subscribed in wishes.items():
                if subscribed:
                    self._subscribe(client_id, channel_id)
                else:
                    self._unsubscribe(client_id, channel_id)
        elif kind == 'advertise':
            self._advertise(event[1], event[2])
        elif kind == 'unadvertise':
            pub = self._client_channels.pop((event[1], event[2]), None)
            if pub is not None and pub.publisher is not None:
                self.node.destroy_publisher(pub.publisher)
        elif kind == 'status':
            self._status(event[1])
        elif kind == 'warn':
            self._warn(event[1])
        elif kind == 'log':
            self._log(event[1])
        elif kind == 'data':
            with self._client_bytes_lock:
                self._client_bytes -= len(event[3])
            self._publish(event[1], event[2], event[3])

    def _wish(self, client_id: int, channel_id: int, subscribed: bool) -> None:
        with self._wishes_lock:
            first = not self._wishes
            self._wishes[(client_id, channel_id)] = subscribed
        if first:
            self._events.put(('wishes',))

    def _graph_changed(self, _entity: Entity, _alive: bool) -> None:
        self._dirty.set()

    def _node_names(self) -> list[str]:
        return sorted(
            {e.node_fqn for e in self.node.context.graph.entities() if e.kind is EntityKind.NODE}
        )

    # -- topics -> channels --------------------------------------------------------------------
    def _visible(self, name: str, patterns: list[re.Pattern[str]]) -> bool:
        return (self.settings.include_hidden or not is_hidden_name(name)) and _matches(
            patterns, name
        )

    def _refresh(self) -> None:
        """Bring channels and services in line with the graph; send the connection graph."""
        from ros2lite.interfaces import definition_text

        entities = [
            e for e in self.node.context.graph.entities() if e.node_fqn != self._own or e.is_node
        ]
        wanted: dict[tuple[str, str], list[Entity]] = {}
        services: dict[str, str] = {}
        for e in entities:
            if not (e.topic_name and e.type_name):
                continue
            if e.kind in (EntityKind.PUBLISHER, EntityKind.SUBSCRIPTION):
                if self._visible(e.topic_name, self._topic_patterns):
                    wanted.setdefault((e.topic_name, e.type_name), []).append(e)
            elif e.kind is EntityKind.SERVICE and self._visible(
                e.topic_name, self._service_patterns
            ):
                services.setdefault(e.topic_name, e.type_name)
        for key in list(self._topics):
            if key not in wanted:
                topic = self._topics.pop(key)
                self._by_channel.pop(topic.channel.id(), None)
                self._unsubscribe_topic(topic)
                topic.channel.close()
        for (name, type_name), _ in sorted(wanted.items()):
            if (name, type_name) in self._topics or type_name in self._unknown_types:
                continue
            try:
                text = definition_text(type_name)
            except Exception as e:  # a type not defined here: no schema a client could use
                self._unknown_types.add(type_name)
                self._warn(f"Topic '{name}': type {type_name} is unknown here ({e}); not shown")
                continue
            schema = foxglove.Schema(name=type_name, encoding='ros2msg', data=text.encode())
            channel = foxglove.Channel(
                name, message_encoding='cdr', schema=schema, context=self._context
            )
            topic = _Topic(name, type_name, channel)
            self._topics[(name, type_name)] = topic
            self._by_channel[channel.id()] = topic
        for (name, type_name), topic in self._topics.items():
            if topic.subscription is not None:
                continue
            if topic.subscribers:  # publishers came back for a channel clients still watch
                self._subscribe_topic(topic, wanted.get((name, type_name), []))
        if 'services' in self._caps:
            self._refresh_services(services)
        if self._graph_subscribed:
            self._publish_graph(entities)

    def _subscribe(self, client_id: int, channel_id: int) -> None:
        topic = self._by_channel.get(channel_id)
        if topic is None:
            return
        topic.subscribers.add(client_id)
        if topic.subscription is None:
            pubs = [
                e
                for e in self.node.context.graph.entities()
                if e.kind is EntityKind.PUBLISHER
                and e.topic_name == topic.name
                and e.type_name == topic.type_name
            ]
            self._subscribe_topic(topic, pubs)

    def _subscribe_topic(self, topic: _Topic, pubs: list[Entity]) -> None:
        from ros2lite.bag.definitions import type_ref
        from ros2lite.monitor.subscription import MonitoredSubscription

        s = self.settings
        depth = sum(p.qos.depth for p in pubs if p.qos is not None)
        depth = min(max(depth, s.min_qos_depth, 1), max(s.max_qos_depth, 1))
        offered = [p.qos for p in pubs if p.qos is not None and p.kind is EntityKind.PUBLISHER]
        qos = match_publishers_qos(
            QoSProfile(history=HistoryPolicy.KEEP_LAST, depth=depth), offered
        ).profile
        hashes = {p.type_hash for p in pubs if p.type_hash}
        msg_type: type | str = topic.type_name
        if len(hashes) == 1:
            # the publishers' own hash, so a type that changed here still matches them
            msg_type = type_ref(topic.type_name, next(iter(hashes)))
        log = topic.channel.base.log
        clock = self.node.get_clock()

        def receive(data: bytes, _attachment: bytes, received: int) -> None:
            if clock.ros_time_is_active:
                received = clock.now().nanoseconds
            log(data, received)

        topic.subscription = MonitoredSubscription(
            self.node, msg_type, topic.name, None, qos, on_payload=receive
        )

    def _unsubscribe(self, client_id: int, channel_id: int) -> None:
        topic = self._by_channel.get(channel_id)
        if topic is None:
            return
        topic.subscribers.discard(client_id)
        if not topic.subscribers:
            self._unsubscribe_topic(topic)

    def _unsubscribe_topic(self, topic: _Topic) -> None:
        sub, topic.subscription = topic.subscription, None
        if sub is not None:
            self.node.destroy_subscription(sub)

    # -- client publishing ---------------------------------------------------------------------
    def _advertise(self, client_id: int, channel: ClientChannel) -> None:
        from ros2lite.interfaces import get_interface

        key = (client_id, channel.id)
        if channel.encoding not in CLIENT_ENCODINGS:
            self._status(f'Unsupported encoding {channel.encoding!r} for {channel.topic}')
            return
        if not _matches(self._client_topic_patterns, channel.topic):
            self._status(f"Topic '{channel.topic}' is not whitelisted for client publishing")
            return
        if sum(1 for c, _ in self._client_channels if c == client_id) >= _CLIENT_CHANNEL_LIMIT:
            self._status(f'A client may advertise {_CLIENT_CHANNEL_LIMIT} channels at most')
            return
        type_name = _type_name(channel.schema_name)
        try:
            msg_class = get_interface(type_name)
            publisher = self.node.create_publisher(msg_class, channel.topic, 10)
        except Exception as e:
            self._status(f"Cannot advertise '{channel.topic}' ({channel.schema_name}): {e}")
            return
        self._client_channels[key] = _ClientPublication(
            channel.topic, type_name, channel.encoding, publisher, msg_class
        )

    def _publish(self, client_id: int, channel_id: int, data: bytes) -> None:
        pub = self._client_channels.get((client_id, channel_id))
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
            self._status(f"Dropped a message to '{pub.topic}': {e}")

    # -- services ------------------------------------------------------------------------------
    def _refresh_services(self, services: dict[str, str]) -> None:
        from ros2lite.interfaces import definition_text

        assert self.server is not None
        gone = [n for n, t in self._services.items() if services.get(n) != t]
        if gone:
            self.server.remove_services(gone)
            for name in gone:
                del self._services[name]
                client = self._service_clients.pop(name, None)
                if client is not None:
                    self.node.destroy_client(client)
        added = []
        for name, type_name in sorted(services.items()):
            if name in self._services or type_name in self._unknown_types:
                continue
            try:
                request = definition_text(f'{type_name}_Request')
                response = definition_text(f'{type_name}_Response')
            except Exception as e:
                self._unknown_types.add(type_name)
                self._warn(f"Service '{name}': type {type_name} is unknown here ({e}); not shown")
                continue
            schema = foxglove.ServiceSchema(
                type_name,
                request=_message_schema(f'{type_name}_Request', request),
                response=_message_schema(f'{type_name}_Response', response),
            )
            added.append(foxglove.Service(name, schema=schema, handler=self._call_service))
            self._services[name] = type_name
        if added:
            self.server.add_services(added)

    def _call_service(self, request: ServiceRequest) -> bytes:
        """A client's call of a graph service, answered with the response's CDR bytes (or an
        error the SDK sends back as a failed call)."""
        from ros2lite.interfaces import get_interface, serialize, set_message_fields
        from ros2lite.interfaces.cdr import service_codecs

        name = request.service_name
        type_name = self._services.get(name)
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
        client = self._service_clients.get(name)
        if client is None:
            client = self.node.create_client(srv, name, fail_without_server=True)
            self._service_clients[name] = client
        response = client.call(msg, timeout_sec=self.settings.service_timeout)
        if response is None:
            raise TimeoutError(f"service '{name}' did not answer in time")
        if request.encoding == 'json':
            from ros2lite.interfaces import message_to_dict

            return json.dumps(message_to_dict(response)).encode()
        return serialize(response)

    # -- parameters ----------------------------------------------------------------------------
    def _on_parameter_event(self, event: Any) -> None:
        node = event.node
        with self._param_lock:
            watched = set(self._param_names)
        changed = []
        from ros2lite.parameter import Parameter

        for p in [*event.new_parameters, *event.changed_parameters]:
            name = f'{node}.{p.name}'
            if name in watched:
                changed.append(to_foxglove(node, Parameter.from_parameter_msg(p)))
        if changed and self.server is not None:
            self.server.publish_parameter_values(changed)

    # -- time ----------------------------------------------------------------------------------
    def _on_clock(self, msg: Any) -> None:
        if self.server is not None:
            self.server.broadcast_time(msg.clock.sec * 1_000_000_000 + msg.clock.nanosec)

    # -- connection graph ----------------------------------------------------------------------
    def _publish_graph(self, entities: list[Entity]) -> None:
        assert self.server is not None
        published: dict[str, set[str]] = {}
        subscribed: dict[str, set[str]] = {}
        provided: dict[str, set[str]] = {}
        table = {
            EntityKind.PUBLISHER: published,
            EntityKind.SUBSCRIPTION: subscribed,
            EntityKind.SERVICE: provided,
        }
        for e in entities:
            into = table.get(e.kind)
            if into is not None and e.topic_name:
                into.setdefault(e.topic_name, set()).add(e.node_fqn)
        picture = tuple(
            tuple(sorted((k, tuple(sorted(v))) for k, v in t.items()))
            for t in (published, subscribed, provided)
        )
        if picture == self._last_graph:
            return
        self._last_graph = picture
        graph = foxglove.ConnectionGraph()
        for topic, ids in published.items():
            graph.set_published_topic(topic, sorted(ids))
        for topic, ids in subscribed.items():
            graph.set_subscribed_topic(topic, sorted(ids))
        for service, ids in provided.items():
            graph.set_advertised_service(service, sorted(ids))
        self.server.publish_connection_graph(graph)

    def tell_clients(self, message: str) -> None:
        """A warning status for every client, sent from the worker (safe on any thread)."""
        self._events.put(('status', message))

    def _status(self, message: str, level: StatusLevel = StatusLevel.Warning) -> None:
        self._warn(message)
        if self.server is not None:
            self.server.publish_status(message, level)

    # -- the SDK's listener (its threads) ------------------------------------------------------
    def on_subscribe(self, client: Client, channel: ChannelView) -> None:
        """A client subscribes to a channel."""
        self._wish(client.id, channel.id, True)

    def on_unsubscribe(self, client: Client, channel: ChannelView) -> None:
        """A client unsubscribes (or left, or the channel went)."""
        self._wish(client.id, channel.id, False)

    def on_client_advertise(self, client: Client, channel: ClientChannel) -> None:
        """A client will publish on a topic."""
        if 'clientPublish' in self._caps:
            self._events.put(('advertise', client.id, channel))

    def on_client_unadvertise(self, client: Client, client_channel_id: int) -> None:
        """A client stops publishing on a channel (or left)."""
        self._events.put(('unadvertise', client.id, client_channel_id))

    def on_message_data(self, client: Client, client_channel_id: int, data: bytes) -> None:
        """A client's message; queued for the worker within a byte budget."""
        with self._client_bytes_lock:
            full = self._client_bytes + len(data) > _CLIENT_DATA_LIMIT
            if not full:
                self._client_bytes += len(data)
        if full:
            self._status('Client messages arrive faster than they can be published; dropped one')
            return
        self._events.put(('data', client.id, client_channel_id, data))

    def on_get_parameters(
        self, client: Client, param_names: list[str], request_id: str | None = None
    ) -> list[foxglove.Parameter]:
        """Values of `/node.param` names (all of them for an empty list)."""
        return self.params.get(param_names)

    def on_set_parameters(
        self, client: Client, parameters: list[foxglove.Parameter], request_id: str | None = None
    ) -> list[foxglove.Parameter]:
        """Set parameters; the values after setting go back to the client."""
        return self.params.set(parameters)

    def on_parameters_subscribe(self, param_names: list[str]) -> None:
        """Clients now watch these parameters (sent on /parameter_events)."""
        with self._param_lock:
            self._param_names.update(n for n in param_names if split_name(n) is not None)

    def on_parameters_unsubscribe(self, param_names: list[str]) -> None:
        """No client watches these parameters any more."""
        with self._param_lock:
            self._param_names.difference_update(param_names)

    def on_connection_graph_subscribe(self) -> None:
        """The first client wants the connection graph: the worker sends it."""
        self._graph_subscribed = True
        self._last_graph = None
        self._dirty.set()

    def on_connection_graph_unsubscribe(self) -> None:
        """No client wants the connection graph any more."""
        self._graph_subscribed = False


class _SdkLog(logging.Handler):
    """The SDK's log: a client whose queue overflowed is told so (a status message); its
    warnings go to the node's log. Every callable only queues for the worker."""

    # a bad client can make the SDK warn thousands of times a second (one per unknown
    # channel id): at most this many warnings a second reach the log
    WARNINGS_PER_SECOND = 5

    def __init__(self, tell: Say, warn: Say, log: Say) -> None:
        super().__init__(logging.INFO)
        self.tell, self.warn, self.log = tell, warn, log
        self._second = 0
        self._warned = 0
        self._suppressed = 0

    def emit(self, record: logging.LogRecord) -> None:
        message = record.getMessage()
        full = _OUTBOX_FULL.search(message)
        if full:
            self.tell(
                f'Send buffer limit reached for client {full[1]}: '
                'its oldest messages are being dropped'
            )
        elif record.levelno >= logging.WARNING:
            self._throttled_warning(message)
        elif 'egistered client' in message:  # (Un)registered client <address>
            self.log(message)

    def _throttled_warning(self, message: str) -> None:
        second = int(time.monotonic())
        if second != self._second:
            if self._suppressed:
                self.warn(f'({self._suppressed} more warnings of the WebSocket server suppressed)')
            self._second, self._warned, self._suppressed = second, 0, 0
        if self._warned < self.WARNINGS_PER_SECOND:
            self._warned += 1
            self.warn(message)
        else:
            self._suppressed += 1


def _follow_sdk_log(tell: Say, warn: Say, log: Say) -> None:
    """Route the SDK's log (Rust's, through Python's logging) to the bridge; the level is
    the SDK's process-wide choice, made once (FOXGLOVE_LOG_LEVEL overrides it)."""
    logger = logging.getLogger('foxglove')
    logger.propagate = False
    for handler in list(logger.handlers):
        if isinstance(handler, _SdkLog):
            logger.removeHandler(handler)
    logger.addHandler(_SdkLog(tell, warn, log))
    foxglove.set_log_level('INFO')


def _message_schema(name: str, text: str) -> foxglove.MessageSchema:
    return foxglove.MessageSchema(
        encoding='cdr', schema=foxglove.Schema(name=name, encoding='ros2msg', data=text.encode())
    )


def _interface(name: str) -> Any:
    from ros2lite.interfaces import get_interface

    return get_interface(name)


def _read(path: str) -> bytes:
    try:
        with open(path, 'rb') as f:
            return f.read()
    except OSError as e:
        raise ValueError(f"cannot read '{path}': {e.strerror}") from None
