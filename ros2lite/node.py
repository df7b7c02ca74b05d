"""Nodes: a name in the graph owning publishers, subscriptions, timers and parameters."""

from __future__ import annotations

import inspect
import time
from collections.abc import Callable
from typing import TYPE_CHECKING, Any, Literal, overload

from ros2lite import names
from ros2lite.arguments import RosArgs, parse_ros_args
from ros2lite.callback_groups import CallbackGroup, MutuallyExclusiveCallbackGroup
from ros2lite.client import Client
from ros2lite.clock import Clock, ClockType
from ros2lite.context import Context, default_context
from ros2lite.executable import Executable, GuardCondition
from ros2lite.logging import RcutilsLogger, set_logger_level
from ros2lite.parameter import Parameter
from ros2lite.parameters.node_api import ParameterMixin
from ros2lite.publisher import Publisher
from ros2lite.qos import (
    QoSProfile,
    ReliabilityPolicy,
    qos_profile_rosout_default,
    qos_profile_services_default,
)
from ros2lite.service import Service
from ros2lite.subscription import Subscription
from ros2lite.timer import Timer
from ros2lite.transport import keys

if TYPE_CHECKING:
    from ros2lite.executable import Destroyable
    from ros2lite.executors import Executor
    from ros2lite.graph import Entity, TopicEndpointInfo
    from ros2lite.msgs.rcl_interfaces.msg import Log
    from ros2lite.msgs.rosgraph_msgs.msg import Clock as ClockMsg
    from ros2lite.service import ServiceCallback
    from ros2lite.subscription import MessageInfo, SubscriptionCallback
    from ros2lite.transport.handles import Handle
    from ros2lite.type_support import MsgT, Srv, SrvRequestT, SrvResponseT

# rcl's rosout profile, lifespan 10 s included: the token must read `:1:,1000:,:10,0:,,`
ROSOUT_QOS = qos_profile_rosout_default
CLOCK_QOS = QoSProfile(reliability=ReliabilityPolicy.BEST_EFFORT, depth=1)


class Node(ParameterMixin):
    """rclpy-shaped node. Create after `ros2lite.init()`; destroy with `destroy_node()`."""

    def __init__(
        self,
        node_name: str,
        *,
        context: Context | None = None,
        cli_args: list[str] | None = None,
        namespace: str | None = None,
        use_global_arguments: bool = True,
        enable_rosout: bool = True,
        parameter_overrides: list[Parameter] | None = None,
        allow_undeclared_parameters: bool = False,
        automatically_declare_parameters_from_overrides: bool = False,
        start_parameter_services: bool = True,
    ) -> None:
        self.context = context or default_context()
        self.context.require()
        args = self.context.args if use_global_arguments else RosArgs()
        self._args = args.merge(parse_ros_args(cli_args)) if cli_args else args
        name = self._args.node_name_override(node_name) or node_name
        ns = self._args.namespace_override(node_name)
        namespace = ns if ns is not None else namespace
        names.validate_node_name(name)
        self._name = name
        self._namespace = names.normalize_namespace(namespace)
        self.node_id = self.context.next_entity_id()
        self.publishers: list[Publisher[Any]] = []
        self.subscriptions: list[Subscription[Any]] = []
        self.timers: list[Timer] = []
        self.services: list[Service[Any, Any]] = []
        self.clients: list[Client[Any, Any]] = []
        self.guards: list[GuardCondition] = []
        self.waitables: list[Executable] = []
        self.default_callback_group: CallbackGroup = MutuallyExclusiveCallbackGroup()
        self._callback_groups: list[CallbackGroup] = [self.default_callback_group]
        # the executor this node was added to (it owns the node's work), and the last one
        # (whose queue may still hold entries of its entities)
        self._executor: Executor | None = None
        self._last_executor: Executor | None = None
        for level_name, level in self._args.log_levels.items():
            set_logger_level(level_name, level)
        from ros2lite.transport.session import declare_token

        self._token: Handle | None = declare_token(
            self.context.require(),
            keys.node_token(
                self.context.domain_id,
                self.context.zid,
                self.node_id,
                self._namespace,
                self._name,
                self.context.enclave,
            ),
        )
        self._clock = Clock(ClockType.ROS_TIME)
        self._clock_sub: Subscription[ClockMsg] | None = None
        self._rosout: Publisher[Log] | None = None
        if enable_rosout:
            self._rosout = self.create_publisher('rcl_interfaces/msg/Log', '/rosout', ROSOUT_QOS)
        self._logger = RcutilsLogger(
            self.get_logger_name(), self._publish_rosout if enable_rosout else None
        )
        self._init_parameters(
            parameter_overrides,
            allow_undeclared_parameters,
            automatically_declare_parameters_from_overrides,
            start_parameter_services,
        )
        self.context.add_node(self)

    # -- names --------------------------------------------------------------------------------
    def get_name(self) -> str:
        """The node's name, after any `__node:=` remapping."""
        return self._name

    def get_namespace(self) -> str:
        """The node's namespace ('/' for none), after any `__ns:=` remapping."""
        return self._namespace

    def get_fully_qualified_name(self) -> str:
        """'/namespace/name', as the graph lists the node."""
        return names.node_fqn(self._namespace, self._name)

    def get_logger_name(self) -> str:
        """The logger name rcl gives the node: namespace dots, then the name."""
        ns = self._namespace.strip('/').replace('/', '.')
        return f'{ns}.{self._name}' if ns else self._name

    def resolve_topic_name(self, topic: str, *, only_expand: bool = False) -> str:
        """Expand a relative/private name and apply remapping rules, as rcl does."""
        return self._resolve(topic, only_expand, is_service=False)

    def _resolve(self, name: str, only_expand: bool, *, is_service: bool) -> str:
        full = names.expand_topic_name(name, self._name, self._namespace, is_service=is_service)
        if only_expand:
            return full
        for rule in self._args.remaps:
            if rule.node not in (None, self._name) or rule.source.startswith('__'):
                continue
            if names.expand_topic_name(rule.source, self._name, self._namespace) == full:
                full = names.expand_topic_name(
                    rule.target, self._name, self._namespace, is_service=is_service
                )
                break
        names.validate_full_topic_name(full, is_service=is_service)
        return full

    # -- executor and callback groups --------------------------------------------------------
    @property
    def executor(self) -> Executor | None:
        """The executor this node was added to, or None."""
        return self._executor

    @executor.setter
    def executor(self, new_executor: Executor | None) -> None:
        """Move the node to another executor (None: to none)."""
        if new_executor is self._executor:
            return
        if self._executor is not None:
            self._executor.remove_node(self)
        if new_executor is not None:
            new_executor.add_node(self)

    @property
    def callback_groups(self) -> list[CallbackGroup]:
        """The groups of this node's entities, its default group first."""
        return list(self._callback_groups)

    def add_waitable(self, waitable: Executable) -> None:
        """Let the executor run `waitable` with this node's entities (action parts do)."""
        self.waitables.append(waitable)
        if waitable._has_work():
            waitable._notify()

    def remove_waitable(self, waitable: Executable) -> None:
        """Stop running `waitable` with this node."""
        if waitable in self.waitables:
            self.waitables.remove(waitable)

    def _executables(self) -> list[Executable]:
        """Everything that queues itself on the executor (timers are found by it)."""
        return [*self.subscriptions, *self.services, *self.clients, *self.guards, *self.waitables]

    def _remember_group(self, group: CallbackGroup | None) -> None:
        if group is not None and group not in self._callback_groups:
            self._callback_groups.append(group)

    def _wake_executor(self) -> None:
        if self._executor is not None:
            self._executor.wake()

    def resolve_service_name(self, service: str, *, only_expand: bool = False) -> str:
        """Services resolve (expansion, remapping) exactly as topics do."""
        return self._resolve(service, only_expand, is_service=True)

    # -- entities -----------------------------------------------------------------------------
    @overload
    def create_publisher(
        self,
        msg_type: type[MsgT],
        topic: str,
        qos_profile: QoSProfile | int,
        *,
        callback_group: CallbackGroup | None = None,
        event_callbacks: object = None,
    ) -> Publisher[MsgT]:
        """A message class gives a publisher typed with it."""

    @overload
    def create_publisher(
        self,
        msg_type: str,
        topic: str,
        qos_profile: QoSProfile | int,
        *,
        callback_group: CallbackGroup | None = None,
        event_callbacks: object = None,
    ) -> Publisher[Any]:
        """A 'pkg/msg/Name' gives a publisher of that type, loosely typed."""

    def create_publisher(
        self,
        msg_type: type[MsgT] | str,
        topic: str,
        qos_profile: QoSProfile | int,
        *,
        callback_group: CallbackGroup | None = None,
        event_callbacks: object = None,
    ) -> Publisher[MsgT]:
        """Publish `msg_type` (a class, or 'pkg/msg/Name') on `topic` (a depth is a
        KEEP_LAST profile of that depth)."""
        pub = Publisher(self, msg_type, topic, qos_profile)
        self.publishers.append(pub)
        return pub

    @overload
    def create_subscription(
        self,
        msg_type: type[MsgT],
        topic: str,
        callback: Callable[[MsgT], object],
        qos_profile: QoSProfile | int,
        *,
        callback_group: CallbackGroup | None = None,
        event_callbacks: object = None,
        raw: Literal[False] = False,
    ) -> Subscription[MsgT]:
        """A message class gives a subscription typed with it."""

    @overload
    def create_subscription(
        self,
        msg_type: str,
        topic: str,
        callback: Callable[[Any], object],
        qos_profile: QoSProfile | int,
        *,
        callback_group: CallbackGroup | None = None,
        event_callbacks: object = None,
        raw: Literal[False] = False,
    ) -> Subscription[Any]:
        """A 'pkg/msg/Name' gives a subscription of that type, loosely typed."""

    @overload
    def create_subscription(
        self,
        msg_type: type[MsgT] | str,
        topic: str,
        callback: Callable[[bytes, MessageInfo], object],
        qos_profile: QoSProfile | int,
        *,
        callback_group: CallbackGroup | None = None,
        event_callbacks: object = None,
        raw: Literal[True],
    ) -> Subscription[MsgT]:
        """raw=True: the callback gets CDR bytes and MessageInfo, undecoded."""

    def create_subscription(
        self,
        msg_type: type[MsgT] | str,
        topic: str,
        callback: SubscriptionCallback[MsgT],
        qos_profile: QoSProfile | int,
        *,
        callback_group: CallbackGroup | None = None,
        event_callbacks: object = None,
        raw: bool = False,
    ) -> Subscription[MsgT]:
        """Call `callback(msg)` on the executor for each message on `topic`; with `raw`,
        `callback(cdr_bytes, MessageInfo)` without decoding."""
        self._remember_group(callback_group)
        sub = Subscription(
            self, msg_type, topic, callback, qos_profile, raw=raw, callback_group=callback_group
        )
        self.subscriptions.append(sub)
        return sub

    def create_timer(
        self,
        timer_period_sec: float,
        callback: Callable[[], object],
        callback_group: CallbackGroup | None = None,
        clock: Clock | None = None,
    ) -> Timer:
        """Call `callback()` every `timer_period_sec` of `clock` (the node's by default)."""
        self._remember_group(callback_group)
        timer = Timer(
            timer_period_sec,
            callback,
            clock or self._clock,
            node=self,
            callback_group=callback_group,
        )
        self.timers.append(timer)
        self._wake_executor()
        return timer

    @overload
    def create_service(
        self,
        srv_type: type[Srv[SrvRequestT, SrvResponseT]],
        srv_name: str,
        callback: ServiceCallback[SrvRequestT, SrvResponseT],
        *,
        qos_profile: QoSProfile = qos_profile_services_default,
        callback_group: CallbackGroup | None = None,
        deferred: bool = False,
    ) -> Service[SrvRequestT, SrvResponseT]:
        """A service class gives a server typed with its request and response."""

    @overload
    def create_service(
        self,
        srv_type: str,
        srv_name: str,
        callback: ServiceCallback[Any, Any],
        *,
        qos_profile: QoSProfile = qos_profile_services_default,
        callback_group: CallbackGroup | None = None,
        deferred: bool = False,
    ) -> Service[Any, Any]:
        """A 'pkg/srv/Name' gives a server of that type, loosely typed."""

    def create_service(
        self,
        srv_type: type[Srv[SrvRequestT, SrvResponseT]] | str,
        srv_name: str,
        callback: ServiceCallback[SrvRequestT, SrvResponseT],
        *,
        qos_profile: QoSProfile = qos_profile_services_default,
        callback_group: CallbackGroup | None = None,
        deferred: bool = False,
    ) -> Service[SrvRequestT, SrvResponseT]:
        """Serve `srv_name`: `callback(request, response)` returns the response (or, with
        `deferred=True`, `callback(request, header)` answers later via `send_response`)."""
        self._remember_group(callback_group)
        srv = Service(
            self,
            srv_type,
            srv_name,
            callback,
            qos_profile,
            callback_group=callback_group,
            deferred=deferred,
        )
        self.services.append(srv)
        return srv

    @overload
    def create_client(
        self,
        srv_type: type[Srv[SrvRequestT, SrvResponseT]],
        srv_name: str,
        *,
        qos_profile: QoSProfile = qos_profile_services_default,
        callback_group: CallbackGroup | None = None,
    ) -> Client[SrvRequestT, SrvResponseT]:
        """A service class gives a client whose call() returns its Response."""

    @overload
    def create_client(
        self,
        srv_type: str,
        srv_name: str,
        *,
        qos_profile: QoSProfile = qos_profile_services_default,
        callback_group: CallbackGroup | None = None,
    ) -> Client[Any, Any]:
        """A 'pkg/srv/Name' gives a client of that type, loosely typed."""

    def create_client(
        self,
        srv_type: type[Srv[SrvRequestT, SrvResponseT]] | str,
        srv_name: str,
        *,
        qos_profile: QoSProfile = qos_profile_services_default,
        callback_group: CallbackGroup | None = None,
    ) -> Client[SrvRequestT, SrvResponseT]:
        """A client of `srv_name`; `call()` blocks for the response, `call_async()` gives
        a future the node's executor completes."""
        self._remember_group(callback_group)
        client = Client(self, srv_type, srv_name, qos_profile, callback_group=callback_group)
        self.clients.append(client)
        return client

    def create_guard_condition(
        self, callback: Callable[[], object], callback_group: CallbackGroup | None = None
    ) -> GuardCondition:
        """A guard whose `trigger()` (from any thread) runs `callback()` on the executor."""
        self._remember_group(callback_group)
        guard = GuardCondition(self, callback, callback_group)
        self.guards.append(guard)
        return guard

    def destroy_publisher(self, pub: Publisher[MsgT]) -> None:
        """Withdraw a publisher of this node."""
        if pub in self.publishers:
            self.publishers.remove(pub)
        pub.destroy()

    def destroy_subscription(self, sub: Subscription[MsgT]) -> None:
        """Withdraw a subscription of this node."""
        if sub in self.subscriptions:
            self.subscriptions.remove(sub)
        sub.destroy()

    def destroy_timer(self, timer: Timer) -> None:
        """Cancel a timer and forget it."""
        timer.cancel()
        if timer in self.timers:
            self.timers.remove(timer)

    def destroy_service(self, srv: Service[SrvRequestT, SrvResponseT]) -> None:
        """Withdraw a service server of this node."""
        if srv in self.services:
            self.services.remove(srv)
        srv.destroy()

    def destroy_client(self, client: Client[SrvRequestT, SrvResponseT]) -> None:
        """Withdraw a service client of this node (its pending calls are cancelled)."""
        if client in self.clients:
            self.clients.remove(client)
        client.destroy()

    def destroy_guard_condition(self, guard: GuardCondition) -> None:
        """Forget a guard condition of this node."""
        if guard in self.guards:
            self.guards.remove(guard)
        guard.destroy()

    def destroy_node(self) -> None:
        """Leave the graph: every entity, timer and waitable of the node goes."""
        from ros2lite.transport.session import undeclare_quietly

        # logging still works once the node is gone (e.g. from a goal thread finishing
        # during shutdown): it just no longer reaches /rosout
        self._rosout = None
        entities: list[Destroyable] = [
            *self.subscriptions,
            *self.publishers,
            *self.services,
            *self.clients,
        ]
        for entity in entities:
            entity.destroy()
        for timer in self.timers:
            timer.cancel()
        for guard in self.guards:
            guard.destroy()
        for waitable in list(self.waitables):  # destroying one may remove it from the list
            destroy: Callable[[], object] | None = getattr(waitable, 'destroy', None)
            if destroy is not None:
                destroy()
        self.subscriptions.clear()
        self.publishers.clear()
        self.timers.clear()
        self.services.clear()
        self.clients.clear()
        self.guards.clear()
        self.waitables.clear()
        undeclare_quietly(self._token)
        self._token = None
        if self._executor is not None:
            self._executor.remove_node(self)
        self.context.remove_node(self)

    # -- time and logging ---------------------------------------------------------------------
    def get_clock(self) -> Clock:
        """The node's ROS clock (simulated time with use_sim_time)."""
        return self._clock

    def get_logger(self) -> RcutilsLogger:
        """The node's logger: console and /rosout."""
        return self._logger

    def _enable_sim_time(self) -> None:
        self._clock._enable_sim_time(True)
        if self._clock_sub is None:
            self._clock_sub = self.create_subscription(
                'rosgraph_msgs/msg/Clock',
                '/clock',
                lambda m: self._clock._set_sim_time(m.clock.sec * 1_000_000_000 + m.clock.nanosec),
                CLOCK_QOS,
            )

    def _publish_rosout(
        self, severity: int, name: str, text: str, caller: inspect.Traceback
    ) -> None:
        if self._rosout is None:
            return
        from ros2lite.interfaces import get_interface

        log = get_interface('rcl_interfaces/msg/Log')
        ns = time.time_ns()
        self._rosout.publish(
            log(
                stamp=get_interface('builtin_interfaces/msg/Time')(
                    sec=ns // 1_000_000_000, nanosec=ns % 1_000_000_000
                ),
                level=severity,
                name=name,
                msg=text,
                file=caller.filename,
                function=caller.function,
                line=caller.lineno,
            )
        )

    # -- graph --------------------------------------------------------------------------------
    def _entities(self) -> list[Entity]:
        entities: list[Entity] = self.context.graph.entities()
        return entities

    def get_node_names(self) -> list[str]:
        """Names of the nodes on the graph."""
        return [n for n, _ in self.get_node_names_and_namespaces()]

    def get_node_names_and_namespaces(self) -> list[tuple[str, str]]:
        """(name, namespace) of the nodes on the graph."""
        from ros2lite.graph import node_names_and_namespaces

        return node_names_and_namespaces(self._entities())

    def get_topic_names_and_types(
        self, include_hidden_topics: bool = False
    ) -> list[tuple[str, list[str]]]:
        """(topic, types) on the graph, hidden topics only when asked."""
        from ros2lite.graph import topic_names_and_types

        return topic_names_and_types(self._entities(), include_hidden_topics)

    def get_service_names_and_types(self) -> list[tuple[str, list[str]]]:
        """(service, types) on the graph."""
        from ros2lite.graph import service_names_and_types

        return service_names_and_types(self._entities(), include_hidden=True)

    def _by_node(
        self, node: str, namespace: str, kind: keys.EntityKind
    ) -> list[tuple[str, list[str]]]:
        from ros2lite.graph import names_and_types_by_node

        return names_and_types_by_node(self._entities(), node, namespace, kind)

    def get_publisher_names_and_types_by_node(
        self, node_name: str, node_namespace: str
    ) -> list[tuple[str, list[str]]]:
        """(topic, types) that node publishes."""
        return self._by_node(node_name, node_namespace, keys.EntityKind.PUBLISHER)

    def get_subscriber_names_and_types_by_node(
        self, node_name: str, node_namespace: str
    ) -> list[tuple[str, list[str]]]:
        """(topic, types) that node subscribes to."""
        return self._by_node(node_name, node_namespace, keys.EntityKind.SUBSCRIPTION)

    def get_service_names_and_types_by_node(
        self, node_name: str, node_namespace: str
    ) -> list[tuple[str, list[str]]]:
        """(service, types) that node serves."""
        return self._by_node(node_name, node_namespace, keys.EntityKind.SERVICE)

    def get_client_names_and_types_by_node(
        self, node_name: str, node_namespace: str
    ) -> list[tuple[str, list[str]]]:
        """(service, types) that node has clients of."""
        return self._by_node(node_name, node_namespace, keys.EntityKind.CLIENT)

    def get_publishers_info_by_topic(self, topic_name: str) -> list[TopicEndpointInfo]:
        """Node, type, GID and QoS of each publisher of a topic."""
        from ros2lite.graph import endpoints_by_topic

        return endpoints_by_topic(
            self._entities(), self.resolve_topic_name(topic_name), keys.EntityKind.PUBLISHER
        )

    def get_subscriptions_info_by_topic(self, topic_name: str) -> list[TopicEndpointInfo]:
        """Node, type, GID and QoS of each subscription of a topic."""
        from ros2lite.graph import endpoints_by_topic

        return endpoints_by_topic(
            self._entities(), self.resolve_topic_name(topic_name), keys.EntityKind.SUBSCRIPTION
        )

    def count_publishers(self, topic_name: str) -> int:
        """How many publishers a topic has on the graph."""
        return len(self.get_publishers_info_by_topic(topic_name))

    def count_subscribers(self, topic_name: str) -> int:
        """How many subscriptions a topic has on the graph."""
        return len(self.get_subscriptions_info_by_topic(topic_name))

    def count_services(self, service_name: str) -> int:
        """How many servers a service has on the graph."""
        from ros2lite.graph import count

        return count(
            self._entities(), self.resolve_service_name(service_name), keys.EntityKind.SERVICE
        )

    def count_clients(self, service_name: str) -> int:
        """How many clients a service has on the graph."""
        from ros2lite.graph import count

        return count(
            self._entities(), self.resolve_service_name(service_name), keys.EntityKind.CLIENT
        )
