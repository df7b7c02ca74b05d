"""Nodes: a name in the graph owning publishers, subscriptions, timers and parameters."""

from __future__ import annotations

import inspect
import time
from collections.abc import Callable
from typing import TYPE_CHECKING, Any, Literal, overload

from ros2lite import names
from ros2lite.callback_groups import CallbackGroup, MutuallyExclusiveCallbackGroup
from ros2lite.client import Client
from ros2lite.clock import Clock, ROSClock
from ros2lite.context import Context, default_context
from ros2lite.graph import GraphMixin
from ros2lite.logging import RcutilsLogger, set_logger_level
from ros2lite.parameter import Parameter
from ros2lite.parameters.node_api import ParameterMixin
from ros2lite.publisher import Publisher
from ros2lite.qos import (
    QoSProfile,
    qos_profile_rosout_default,
    qos_profile_services_default,
)
from ros2lite.rate import Rate
from ros2lite.runtime.arguments import RosArgs, parse_ros_args
from ros2lite.runtime.executable import Executable, GuardCondition, NodeExecutor
from ros2lite.runtime.parking import Parking
from ros2lite.runtime.scheduling import NodeWork
from ros2lite.service import Service
from ros2lite.subscription import Subscription
from ros2lite.timer import Timer
from ros2lite.transport import keys

if TYPE_CHECKING:
    from ros2lite.event_handler import PublisherEventCallbacks, SubscriptionEventCallbacks
    from ros2lite.logging_service import LoggingService
    from ros2lite.msgs.rcl_interfaces.msg import Log
    from ros2lite.qos_overriding_options import QoSOverridingOptions
    from ros2lite.runtime.executable import Destroyable
    from ros2lite.service import ServiceCallback
    from ros2lite.subscription import MessageInfo, SubscriptionCallback
    from ros2lite.transport.handles import Handle
    from ros2lite.type_support import MsgT, Srv, SrvRequestT, SrvResponseT

# rcl's rosout profile, lifespan 10 s included: the token must read `:1:,1000:,:10,0:,,`
ROSOUT_QOS = qos_profile_rosout_default


class Node(ParameterMixin, GraphMixin):
    """rclpy-shaped node. Create after `ros2lite.init()`; destroy with `destroy_node()`."""

    # rclpy's default QoS event callbacks (warnings, fed by the live graph); a tool's node
    # (ros2lite.tools.connection) goes without them, and without a graph cache of its own
    _default_event_callbacks = True
    context: Context
    """The context the node lives in (GraphMixin asks it only for the graph)."""

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
        enable_logger_service: bool = False,
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
        self.rates: list[Rate] = []
        self.waitables: list[Executable] = []
        self.default_callback_group: CallbackGroup = MutuallyExclusiveCallbackGroup()
        self._callback_groups: list[CallbackGroup] = [self.default_callback_group]
        # who runs the node's work: the executor it is attached to, what waits for one
        self.work: NodeWork[NodeExecutor[Node]] = NodeWork(self._executables, self.waitables)
        # where its single-threaded executor waits when idle: its kept channels
        self.parking = Parking(self.work.notify)
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
        self._clock = ROSClock()
        self._rosout: Publisher[Log] | None = None
        enable_rosout = enable_rosout and self._args.rosout_logs is not False
        if enable_rosout:
            # rcl's own publisher: not one of the node's `publishers`, no event handlers
            self._rosout = Publisher(self, 'rcl_interfaces/msg/Log', '/rosout', ROSOUT_QOS)
        self._logger = RcutilsLogger(
            self.get_logger_name(), self._publish_rosout if enable_rosout else None
        )
        self._init_parameters(
            self._args,
            parameter_overrides,
            allow_undeclared_parameters,
            automatically_declare_parameters_from_overrides,
            start_parameter_services,
        )
        from ros2lite.time_source import TimeSource

        # use_sim_time (declared here unless an override did) and /clock, as rclpy's nodes do
        self._time_source = TimeSource(node=self)
        self._time_source.attach_clock(self._clock)
        from ros2lite.type_description_service import TypeDescriptionService

        self._type_description_service = TypeDescriptionService(self)
        self._logger_service: LoggingService | None = None
        if enable_logger_service:
            from ros2lite.logging_service import LoggingService

            self._logger_service = LoggingService(self)
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
    def executor(self) -> NodeExecutor[Node] | None:
        """The executor this node was last added to, or None. It stays after the node is
        removed from it (as in rclpy), so tasks created there, such as a deferred action
        goal's execution, run when that executor spins again."""
        work = self.work
        return work.executor if work.executor is not None else work.last_executor

    @executor.setter
    def executor(self, new_executor: NodeExecutor[Node] | None) -> None:
        """Move the node to `new_executor` (None: to no executor at all)."""
        current = self.executor
        if new_executor is current:
            return
        if current is not None:
            current.remove_node(self)
        self.work.forget()
        if new_executor is not None:
            new_executor.add_node(self)
            self.work.handed_to(new_executor)

    @property
    def callback_groups(self) -> list[CallbackGroup]:
        """The groups of this node's entities, its default group first."""
        return list(self._callback_groups)

    def add_waitable(self, waitable: Executable) -> None:
        """Run `waitable` with this node's entities (its executor, its groups); action
        clients and servers are such waitables."""
        self._add_waitable(waitable, joined=waitable.settle_owner(self) is None)

    def _add_waitable(self, waitable: Executable, *, joined: bool) -> None:
        if joined:  # it had no node: its group is this node's now
            self._remember_group(waitable.callback_group)
        self.waitables.append(waitable)
        self.work.notify_if_ready(waitable)

    def adopt(self, entity: Executable) -> None:
        """Make an entity built outside this node's factories its own (a tool's subscription
        class, say): destroyed with the node, its group remembered and, if it has work
        already, queued on the node's executor. An entity of another node is refused; one
        without a node (a waitable) is added as add_waitable() does."""
        owner = entity.settle_owner(self)
        if owner is not None and owner is not self:
            raise ValueError('the entity belongs to another node')
        # the node's list of the entity's kind
        kinds: tuple[tuple[type, list[Any]], ...] = (
            (Subscription, self.subscriptions),
            (Service, self.services),
            (Client, self.clients),
            (Timer, self.timers),
            (GuardCondition, self.guards),
        )
        entities = next((own for kind, own in kinds if isinstance(entity, kind)), None)
        if entities is None:
            if entity not in self.waitables:
                self._add_waitable(entity, joined=owner is None)
            return
        if entity in entities:
            return
        entities.append(entity)
        self._remember_group(entity.callback_group)
        if isinstance(entity, Timer):
            self.work.wake()  # a spinning executor must see its deadline
        else:
            self.work.notify_if_ready(entity)

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
        event_callbacks: PublisherEventCallbacks | None = None,
        qos_overriding_options: QoSOverridingOptions | None = None,
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
        event_callbacks: PublisherEventCallbacks | None = None,
        qos_overriding_options: QoSOverridingOptions | None = None,
    ) -> Publisher[Any]:
        """A 'pkg/msg/Name' gives a publisher of that type, loosely typed."""

    def create_publisher(
        self,
        msg_type: type[MsgT] | str,
        topic: str,
        qos_profile: QoSProfile | int,
        *,
        callback_group: CallbackGroup | None = None,
        event_callbacks: PublisherEventCallbacks | None = None,
        qos_overriding_options: QoSOverridingOptions | None = None,
    ) -> Publisher[MsgT]:
        """Publish `msg_type` (a class, or 'pkg/msg/Name') on `topic` (a depth is a
        KEEP_LAST profile of that depth); with `qos_overriding_options` its QoS may be
        overridden by parameters (see :mod:`ros2lite.qos_overriding_options`)."""
        from ros2lite.qos_overriding_options import qos_with_overrides

        qos_profile = qos_with_overrides(
            Publisher, self, topic, qos_profile, qos_overriding_options
        )
        pub = Publisher(self, msg_type, topic, qos_profile)
        self.publishers.append(pub)
        self._add_event_handlers(pub, event_callbacks, callback_group, topic)
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
        event_callbacks: SubscriptionEventCallbacks | None = None,
        qos_overriding_options: QoSOverridingOptions | None = None,
        raw: Literal[False] = False,
    ) -> Subscription[MsgT]:
        """A message class gives a subscription typed with it."""

    @overload
    def create_subscription(
        self,
        msg_type: type[MsgT],
        topic: str,
        callback: Callable[[MsgT, MessageInfo], object],
        qos_profile: QoSProfile | int,
        *,
        callback_group: CallbackGroup | None = None,
        event_callbacks: SubscriptionEventCallbacks | None = None,
        qos_overriding_options: QoSOverridingOptions | None = None,
        raw: Literal[False] = False,
    ) -> Subscription[MsgT]:
        """`callback(msg, info)`: the message and its MessageInfo (rclpy's second form)."""

    @overload
    def create_subscription(
        self,
        msg_type: str,
        topic: str,
        callback: Callable[..., object],
        qos_profile: QoSProfile | int,
        *,
        callback_group: CallbackGroup | None = None,
        event_callbacks: SubscriptionEventCallbacks | None = None,
        qos_overriding_options: QoSOverridingOptions | None = None,
        raw: Literal[False] = False,
    ) -> Subscription[Any]:
        """A 'pkg/msg/Name' gives a subscription of that type, loosely typed."""

    @overload
    def create_subscription(
        self,
        msg_type: type[MsgT] | str,
        topic: str,
        callback: Callable[[bytes], object] | Callable[[bytes, MessageInfo], object],
        qos_profile: QoSProfile | int,
        *,
        callback_group: CallbackGroup | None = None,
        event_callbacks: SubscriptionEventCallbacks | None = None,
        qos_overriding_options: QoSOverridingOptions | None = None,
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
        event_callbacks: SubscriptionEventCallbacks | None = None,
        qos_overriding_options: QoSOverridingOptions | None = None,
        raw: bool = False,
    ) -> Subscription[MsgT]:
        """Call `callback(msg)` (or `callback(msg, info)`, told apart by its signature) on
        the executor for each message on `topic`; with `raw`, the message is its CDR bytes,
        undecoded."""
        from ros2lite.qos_overriding_options import qos_with_overrides

        qos_profile = qos_with_overrides(
            Subscription, self, topic, qos_profile, qos_overriding_options
        )
        self._remember_group(callback_group)
        sub = Subscription(
            self, msg_type, topic, callback, qos_profile, raw=raw, callback_group=callback_group
        )
        self.subscriptions.append(sub)
        self._add_event_handlers(sub, event_callbacks, callback_group, topic)
        return sub

    def _add_event_handlers(
        self,
        entity: Publisher[MsgT] | Subscription[MsgT],
        callbacks: PublisherEventCallbacks | SubscriptionEventCallbacks | None,
        group: CallbackGroup | None,
        topic: str,
    ) -> None:
        """The entity's QoS event handlers (rclpy's defaults warn of incompatible QoS and
        types; tools' hidden nodes go without them)."""
        from ros2lite.event_handler import PublisherEventCallbacks, SubscriptionEventCallbacks

        if callbacks is None:
            defaults = self._default_event_callbacks
            callbacks = (
                PublisherEventCallbacks(use_default_callbacks=defaults)
                if isinstance(entity, Publisher)
                else SubscriptionEventCallbacks(use_default_callbacks=defaults)
            )
        entity.event_handlers = callbacks.create_event_handlers(group, entity, topic)
        for handler in entity.event_handlers:
            self.add_waitable(handler)

    def create_timer(
        self,
        timer_period_sec: float,
        callback: Callable[[], object],
        callback_group: CallbackGroup | None = None,
        clock: Clock | None = None,
        autostart: bool = True,
    ) -> Timer:
        """Call `callback()` every `timer_period_sec` of `clock` (the node's ROS clock by
        default); `autostart=False` leaves it canceled until `reset()`."""
        self._remember_group(callback_group)
        timer = Timer(
            timer_period_sec,
            callback,
            clock or self._clock,
            node=self,
            callback_group=callback_group,
            autostart=autostart,
        )
        self.timers.append(timer)
        self.work.wake()
        return timer

    def create_rate(self, frequency: float, clock: Clock | None = None) -> Rate:
        """A Rate ticking at `frequency` Hz on this node (which another thread spins)."""
        rate = Rate(self, frequency, clock)
        self.rates.append(rate)
        return rate

    def destroy_rate(self, rate: Rate) -> bool:
        """Destroy it; True if it was this node's (rclpy's answer)."""
        if rate not in self.rates:
            return False
        self.rates.remove(rate)
        rate.destroy()
        return True

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
        fail_without_server: bool = False,
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
        fail_without_server: bool = False,
    ) -> Client[Any, Any]:
        """A 'pkg/srv/Name' gives a client of that type, loosely typed."""

    def create_client(
        self,
        srv_type: type[Srv[SrvRequestT, SrvResponseT]] | str,
        srv_name: str,
        *,
        qos_profile: QoSProfile = qos_profile_services_default,
        callback_group: CallbackGroup | None = None,
        fail_without_server: bool = False,
    ) -> Client[SrvRequestT, SrvResponseT]:
        """A client of `srv_name`; `call()` blocks for the response, `call_async()` gives
        a future the node's executor completes. See :class:`~ros2lite.client.Client` for
        `fail_without_server` (a ros2lite extra for tools)."""
        self._remember_group(callback_group)
        client = Client(
            self,
            srv_type,
            srv_name,
            qos_profile,
            callback_group=callback_group,
            fail_without_server=fail_without_server,
        )
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

    def destroy_publisher(self, pub: Publisher[MsgT]) -> bool:
        """Withdraw a publisher of this node; True if it was this node's (rclpy's answer)."""
        if pub not in self.publishers:
            return False
        self.publishers.remove(pub)
        pub.destroy()
        return True

    def destroy_subscription(self, sub: Subscription[MsgT]) -> bool:
        """Withdraw a subscription of this node; True if it was this node's (rclpy's
        answer)."""
        if sub not in self.subscriptions:
            return False
        self.subscriptions.remove(sub)
        sub.destroy()
        return True

    def destroy_timer(self, timer: Timer) -> bool:
        """Cancel a timer and forget it; True if it was this node's."""
        timer.cancel()
        if timer not in self.timers:
            return False
        self.timers.remove(timer)
        return True

    def destroy_service(self, srv: Service[SrvRequestT, SrvResponseT]) -> bool:
        """Withdraw a service server of this node; True if it was this node's (rclpy's
        answer)."""
        if srv not in self.services:
            return False
        self.services.remove(srv)
        srv.destroy()
        return True

    def destroy_client(self, client: Client[SrvRequestT, SrvResponseT]) -> bool:
        """Withdraw a service client of this node (its pending calls are cancelled); True if
        it was this node's (rclpy's answer)."""
        if client not in self.clients:
            return False
        self.clients.remove(client)
        client.destroy()
        return True

    def destroy_guard_condition(self, guard: GuardCondition) -> bool:
        """Forget a guard condition of this node; True if it was this node's (rclpy's
        answer)."""
        if guard not in self.guards:
            return False
        self.guards.remove(guard)
        guard.destroy()
        return True

    def destroy_node(self) -> None:
        """Leave the graph: every entity, timer and waitable of the node goes."""
        from ros2lite.transport.session import undeclare_quietly

        # logging still works once the node is gone (e.g. from a goal thread finishing
        # during shutdown): it just no longer reaches /rosout
        rosout, self._rosout = self._rosout, None
        if rosout is not None:
            rosout.destroy()
        entities: list[Destroyable] = [
            *self.subscriptions,
            *self.publishers,
            *self.services,
            *self.clients,
        ]
        for entity in entities:
            entity.destroy()
        for rate in self.rates:
            rate.destroy()
        self.rates.clear()
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
        executor = self.work.executor
        if executor is not None:
            executor.remove_node(self)
        self.parking.close()
        self.context.remove_node(self)

    # -- time and logging ---------------------------------------------------------------------
    def get_clock(self) -> Clock:
        """The node's ROS clock (simulated time with use_sim_time)."""
        return self._clock

    def get_logger(self) -> RcutilsLogger:
        """The node's logger: console and /rosout."""
        return self._logger

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
