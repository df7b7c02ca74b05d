"""The bridge: a ROS node that shows its graph to Foxglove clients through `foxglove-sdk`.

Every topic of the graph is a channel (`cdr` messages, the `ros2msg` schema with its full
dependency text, as our bags write it); a topic is subscribed in Zenoh only while some client
subscribes to its channel, and samples go from the receive thread to the SDK as CDR bytes,
never decoded. The SDK queues them per client and drops the oldest when a client falls
behind, so a slow client never pushes back on the robot.

The bridge is parts over one `BridgeState`: channels, client publishing, services,
parameters and assets, each an object of its module. The SDK calls the listener (this class)
on its own threads, and serves no other client while a listener call runs: anything that
declares or undeclares something in Zenoh (subscribing, a client's publishers, the graph's
channels and services) is handed to one worker thread, parameters are asked on a thread of
their own and answered within a short bound. Service calls and assets run on the SDK's
blocking pool, each with a deadline or a size bound. A front (`front.py`) takes clients that
offer only the protocol's older name.
"""

from __future__ import annotations

import logging
import queue
import re
import threading
import time
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

import foxglove
from foxglove.websocket import (
    Capability,
    ChannelView,
    Client,
    ClientChannel,
    ServerListener,
    WebSocketServer,
)

from ros2lite.bundled.foxglove_bridge.assets import PackageAssets
from ros2lite.bundled.foxglove_bridge.channels import GraphChannels
from ros2lite.bundled.foxglove_bridge.front import SubprotocolFront
from ros2lite.bundled.foxglove_bridge.parameters import RemoteParameters
from ros2lite.bundled.foxglove_bridge.publishing import CLIENT_ENCODINGS, ClientPublishing
from ros2lite.bundled.foxglove_bridge.services import GraphServices
from ros2lite.bundled.foxglove_bridge.state import (
    DEFAULT_CAPABILITIES,
    BridgeState,
    Say,
    Settings,
    compile_patterns,
)
from ros2lite.graph import EntityKind

if TYPE_CHECKING:
    from ros2lite.graph import Entity
    from ros2lite.msgs.rcl_interfaces.msg import ParameterEvent
    from ros2lite.msgs.rosgraph_msgs.msg import Clock
    from ros2lite.node import Node
    from ros2lite.subscription import Subscription

__all__ = ['CAPABILITIES', 'DEFAULT_CAPABILITIES', 'Bridge', 'Settings', 'compile_patterns']

# capability names of the C++ bridge's `capabilities` parameter -> the SDK's ('assets' is
# the SDK's own choice: it offers it when given an asset handler)
CAPABILITIES = {
    'clientPublish': Capability.ClientPublish,
    'parameters': Capability.Parameters,
    'parametersSubscribe': Capability.Parameters,
    'services': Capability.Services,
    'connectionGraph': Capability.ConnectionGraph,
    'time': Capability.Time,
}
# how often the graph is looked at when no change was heard (seconds)
_REFRESH_PERIOD = 1.0
# what the SDK logs (at INFO) when a client's queue overflowed and it dropped the oldest
_OUTBOX_FULL = re.compile(r'outbox for client (\S+) full')
# a client's queued publish data beyond this is dropped (bytes), so a flood cannot grow memory
_CLIENT_DATA_LIMIT = 64 * 1024 * 1024


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
        caps = set(settings.capabilities)
        unknown = caps - set(CAPABILITIES) - {'assets'}
        if unknown:
            raise ValueError(f'unknown capabilities: {", ".join(sorted(unknown))}')
        self.state = state = BridgeState(
            node=node,
            settings=settings,
            context=foxglove.Context(),
            own=node.get_fully_qualified_name(),
            capabilities=caps,
            warn=warn or node.get_logger().warning,
            log=log or node.get_logger().info,
        )
        if settings.send_buffer_limit != Settings.send_buffer_limit:
            state.warn(
                'send_buffer_limit (bytes) is not used: foxglove-sdk bounds each client\'s '
                'queue by message_backlog_size (messages)'
            )
        self.channels = GraphChannels(
            state, compile_patterns(settings.topic_whitelist, 'topic_whitelist')
        )
        self.services = GraphServices(
            state, compile_patterns(settings.service_whitelist, 'service_whitelist')
        )
        self.publishing = ClientPublishing(
            state, compile_patterns(settings.client_topic_whitelist, 'client_topic_whitelist')
        )
        self.params = RemoteParameters(
            node,
            self._node_names,
            compile_patterns(settings.param_whitelist, 'param_whitelist'),
            ignore_unresponsive=settings.ignore_unresponsive_param_nodes,
            warn=state.warn,
        )
        self.assets: PackageAssets | None = None
        if 'assets' in caps:
            self.assets = PackageAssets(
                compile_patterns(settings.asset_uri_allowlist, 'asset_uri_allowlist')
            )
        self.front: SubprotocolFront | None = None
        self._client_bytes = 0
        self._client_bytes_lock = threading.Lock()
        self._events: queue.Queue[tuple[Any, ...]] = queue.Queue()
        # (client, channel) -> subscribed, the latest wish only: a client flipping a
        # subscription a million times leaves one entry, not a million events
        self._wishes: dict[tuple[int, int], bool] = {}
        self._wishes_lock = threading.Lock()
        self._dirty = threading.Event()
        self._stopping = threading.Event()
        self._worker: threading.Thread | None = None
        self._param_events: Subscription[ParameterEvent] | None = None
        self._clock_sub: Subscription[Clock] | None = None

    @property
    def server(self) -> WebSocketServer | None:
        """The SDK's server, once started."""
        return self.state.server

    @property
    def node(self) -> Node:
        """The bridge's node."""
        return self.state.node

    @property
    def settings(self) -> Settings:
        """The bridge's parameters."""
        return self.state.settings

    # -- life ----------------------------------------------------------------------------------
    def start(self) -> WebSocketServer:
        """Open the server and start following the graph."""
        state = self.state
        s = state.settings
        names = {c for c in state.capabilities if c in CAPABILITIES}
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
        # without TLS the front listens where we were told and the SDK on a loopback port of
        # its own (the front reads the upgrade request); with TLS the SDK listens itself and
        # only the protocol's current name is taken
        front = not s.tls
        server = foxglove.start_server(
            name=state.own,
            host='127.0.0.1' if front else s.address,
            port=0 if front else s.port,
            capabilities=capabilities,
            server_listener=self,
            supported_encodings=list(CLIENT_ENCODINGS),
            asset_handler=self.assets.fetch if self.assets is not None else None,
            context=state.context,
            message_backlog_size=max(1, s.message_backlog_size),
            tls_cert=cert,
            tls_key=key,
        )
        state.server = server
        if front:
            try:
                self.front = SubprotocolFront(
                    s.address,
                    s.port,
                    server.port,
                    warn=lambda m: self._events.put(('warn', m)),
                    log=lambda m: self._events.put(('log', m)),
                )
            except (RuntimeError, OSError) as e:
                server.stop()
                state.server = None
                raise RuntimeError(str(e)) from None
            self.front.start()
        self.params.start()
        state.node.context.graph.add_listener(self._graph_changed)
        if 'parametersSubscribe' in state.capabilities:
            self._param_events = state.node.create_subscription(
                _interface('rcl_interfaces/msg/ParameterEvent'),
                '/parameter_events',
                self._on_parameter_event,
                10,
            )
        if s.use_sim_time:
            self._clock_sub = state.node.create_subscription(
                _interface('rosgraph_msgs/msg/Clock'), '/clock', self._on_clock, 10
            )
        self._refresh()
        self._worker = threading.Thread(target=self._work, name='foxglove-bridge', daemon=True)
        self._worker.start()
        scheme = 'wss' if s.tls else 'ws'
        state.log(f'Foxglove bridge listening on {scheme}://{s.address}:{self.port}')
        return server

    @property
    def port(self) -> int:
        """The port clients connect to (the chosen one when `port` was 0)."""
        if self.front is not None:
            return self.front.port
        assert self.state.server is not None
        return self.state.server.port

    def close(self) -> None:
        """Stop serving: the server, the worker, every subscription and publisher we made."""
        self._stopping.set()
        self.state.node.context.graph.remove_listener(self._graph_changed)
        if self._worker is not None:
            self._events.put(('stop',))
            self._worker.join(5.0)
        if self.front is not None:
            self.front.close()
        if self.state.server is not None:
            self.state.server.stop()
        self.params.close()
        self.channels.close()

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
                self.state.warn(f'foxglove_bridge: {e}')

    def _refresh(self) -> None:
        """Channels and services in line with the graph (our own entities left out)."""
        state = self.state
        entities = [
            e for e in state.node.context.graph.entities() if e.node_fqn != state.own or e.is_node
        ]
        self.channels.refresh(entities)
        if 'services' in state.capabilities:
            self.services.refresh(entities)

    def _handle(self, event: tuple[Any, ...]) -> None:
        kind = event[0]
        if kind == 'wishes':
            with self._wishes_lock:
                wishes, self._wishes = self._wishes, {}
            for (client_id, channel_id), subscribed in wishes.items():
                if subscribed:
                    self.channels.subscribe(client_id, channel_id)
                else:
                    self.channels.unsubscribe(client_id, channel_id)
        elif kind == 'advertise':
            self.publishing.advertise(event[1], event[2])
        elif kind == 'unadvertise':
            self.publishing.unadvertise(event[1], event[2])
        elif kind == 'status':
            self.state.status(event[1])
        elif kind == 'warn':
            self.state.warn(event[1])
        elif kind == 'log':
            self.state.log(event[1])
        elif kind == 'data':
            with self._client_bytes_lock:
                self._client_bytes -= len(event[3])
            self.publishing.publish(event[1], event[2], event[3])

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
            {
                e.node_fqn
                for e in self.state.node.context.graph.entities()
                if e.kind is EntityKind.NODE
            }
        )

    # -- parameters and time (the executor's thread) -------------------------------------------
    def _on_parameter_event(self, event: ParameterEvent) -> None:
        changed = self.params.on_event(event)
        if changed and self.state.server is not None:
            self.state.server.publish_parameter_values(changed)

    def _on_clock(self, msg: Clock) -> None:
        if self.state.server is not None:
            self.state.server.broadcast_time(msg.clock.sec * 1_000_000_000 + msg.clock.nanosec)

    def tell_clients(self, message: str) -> None:
        """A warning status for every client, sent from the worker (safe on any thread)."""
        self._events.put(('status', message))

    # -- the SDK's listener (its threads) ------------------------------------------------------
    def on_subscribe(self, client: Client, channel: ChannelView) -> None:
        """A client subscribes to a channel."""
        self._wish(client.id, channel.id, True)

    def on_unsubscribe(self, client: Client, channel: ChannelView) -> None:
        """A client unsubscribes (or left, or the channel went)."""
        self._wish(client.id, channel.id, False)

    def on_client_advertise(self, client: Client, channel: ClientChannel) -> None:
        """A client will publish on a topic."""
        if 'clientPublish' in self.state.capabilities:
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
            self.state.status(
                'Client messages arrive faster than they can be published; dropped one'
            )
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
        self.params.watch(param_names)

    def on_parameters_unsubscribe(self, param_names: list[str]) -> None:
        """No client watches these parameters any more."""
        self.params.unwatch(param_names)

    def on_connection_graph_subscribe(self) -> None:
        """The first client wants the connection graph: the worker sends it."""
        self.channels.graph_subscribed = True
        self.channels.last_graph = None
        self._dirty.set()

    def on_connection_graph_unsubscribe(self) -> None:
        """No client wants the connection graph any more."""
        self.channels.graph_subscribed = False


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


def _interface(name: str) -> Any:
    from ros2lite.interfaces import get_interface

    return get_interface(name)


def _read(path: str) -> bytes:
    try:
        with open(path, 'rb') as f:
            return f.read()
    except OSError as e:
        raise ValueError(f"cannot read '{path}': {e.strerror}") from None
