"""Managed (lifecycle) nodes with rclpy's API, serving the five lifecycle services.

A `LifecycleNode` starts `unconfigured`. A transition (asked through `trigger_*()` or the
`~/change_state` service) moves it into a transition state, runs the matching `on_*`
callback, and follows `transition_success|failure|error` to the next primary state; an error
runs `on_error` from `errorprocessing`. Every state change is announced on
`~/transition_event` exactly as rcl_lifecycle does it (start and goal state only), so tools
that drive C++ managed nodes drive these too.
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from typing import TYPE_CHECKING, Any, TypeVar

from ros2lite.lifecycle.managed_entity import ManagedEntity
from ros2lite.lifecycle.publisher import LifecyclePublisher
from ros2lite.lifecycle.state_machine import (
    ACTIVATING,
    CLEANINGUP,
    CONFIGURING,
    DEACTIVATING,
    ERRORPROCESSING,
    SHUTTINGDOWN,
    STATES,
    TRANSITIONS,
    InvalidTransitionError,
    LifecycleState,
    StateMachine,
    TransitionCallbackReturn,
    TransitionDef,
)
from ros2lite.node import Node
from ros2lite.qos import QoSProfile, qos_profile_services_default

if TYPE_CHECKING:
    from typing_extensions import Unpack

    from ros2lite.callback_groups import CallbackGroup
    from ros2lite.msgs.lifecycle_msgs import msg as lc_msg
    from ros2lite.msgs.lifecycle_msgs import srv as lc_srv
    from ros2lite.node_options import NodeOptions
    from ros2lite.publisher import Publisher
    from ros2lite.type_support import MsgT

__all__ = ['LifecycleNode', 'LifecycleNodeMixin']

TransitionCallback = Callable[[LifecycleState], TransitionCallbackReturn]
_Response = TypeVar('_Response')

# rcl_lifecycle publishes transition events with rcl's default publisher options
TRANSITION_EVENT_QOS = QoSProfile(depth=10)


def _msg(name: str) -> Any:  # the lifecycle_msgs class of 'msg/Name' or 'srv/Name'
    from ros2lite.interfaces import get_interface

    return get_interface(f'lifecycle_msgs/{name}')


class LifecycleNodeMixin:
    """The lifecycle part of a node: state machine, callbacks, managed entities, services.

    Mixed into a :class:`ros2lite.node.Node` (after the node is built), as rclpy does; the
    services run in `callback_group` (default: the node's)."""

    def __init__(
        self,
        *,
        enable_communication_interface: bool = True,
        callback_group: CallbackGroup | None = None,
    ) -> None:
        if not isinstance(enable_communication_interface, bool):
            raise TypeError('enable_communication_interface must be a bool')
        node: Node = self  # type: ignore[assignment]
        self._state_machine = StateMachine()
        self._transition_lock = threading.RLock()
        self._managed_entities: set[ManagedEntity] = set()
        self._callbacks: dict[int, TransitionCallback] = {
            CONFIGURING: self.on_configure,
            CLEANINGUP: self.on_cleanup,
            SHUTTINGDOWN: self.on_shutdown,
            ACTIVATING: self.on_activate,
            DEACTIVATING: self.on_deactivate,
            ERRORPROCESSING: self.on_error,
        }
        self._transition_event_pub: Publisher[lc_msg.TransitionEvent] | None = None
        if not enable_communication_interface:
            return
        self._transition_event_pub = node.create_publisher(
            _msg('msg/TransitionEvent'), '~/transition_event', TRANSITION_EVENT_QOS
        )
        options: dict[str, Any] = {  # the keywords of create_service
            'qos_profile': qos_profile_services_default,
            'callback_group': callback_group,
        }
        machine = self._state_machine
        # rcl_lifecycle's five services: (name, type, callback); but for change_state, each
        # only reads the machine into one field of its response
        services: tuple[tuple[str, str, Callable[..., object]], ...] = (
            ('change_state', 'ChangeState', self._on_change_state),
            ('get_state', 'GetState', _query('current_state', lambda: _state_msg(machine.current))),
            (
                'get_available_states',
                'GetAvailableStates',
                _query('available_states', lambda: [_state_msg(s) for s in STATES]),
            ),
            (
                'get_available_transitions',
                'GetAvailableTransitions',
                _query(
                    'available_transitions',
                    lambda: [_description(t) for t in machine.available_transitions()],
                ),
            ),
            (
                'get_transition_graph',
                'GetAvailableTransitions',
                _query('available_transitions', lambda: [_description(t) for t in TRANSITIONS]),
            ),
        )
        for name, type_name, callback in services:
            service = node.create_service(
                _msg(f'srv/{type_name}'), f'~/{name}', callback, **options
            )
            # rclpy's attributes: the node's `_service_<name>`, the machine's `service_<name>`
            setattr(self, f'_service_{name}', service)
            setattr(machine, f'service_{name}', service)

    # -- the user's side ------------------------------------------------------------------------
    @property
    def current_state(self) -> LifecycleState:
        """Where the node is now."""
        state_id, label = self._state_machine.current_state
        return LifecycleState(label, state_id)

    def register_callback(self, state_id: int, callback: TransitionCallback) -> None:
        """Run `callback(previous_state)` when the node enters the transition state
        `state_id` (instead of the `on_*` method)."""
        if state_id not in self._callbacks:
            raise ValueError(f'{state_id} is not a transition state id')
        self._callbacks[state_id] = callback

    def add_managed_entity(self, entity: ManagedEntity) -> None:
        """Let `entity` follow the node's activation (the default on_activate/on_deactivate
        switch every managed entity)."""
        if not isinstance(entity, ManagedEntity):
            raise TypeError('entity must be a ManagedEntity')
        self._managed_entities.add(entity)

    def create_lifecycle_publisher(
        self, msg_type: type[MsgT] | str, topic: str, qos_profile: QoSProfile | int, **_: object
    ) -> LifecyclePublisher[MsgT]:
        """A publisher that publishes only while the node is active."""
        node: Node = self  # type: ignore[assignment]
        pub = LifecyclePublisher(node, msg_type, topic, qos_profile)
        node.publishers.append(pub)
        self._managed_entities.add(pub)
        return pub

    def destroy_lifecycle_publisher(self, publisher: LifecyclePublisher[MsgT]) -> None:
        """Destroy a publisher made by :meth:`create_lifecycle_publisher`."""
        self._managed_entities.discard(publisher)
        node: Node = self  # type: ignore[assignment]
        node.destroy_publisher(publisher)

    def trigger_configure(self) -> TransitionCallbackReturn:
        """unconfigured → inactive (via on_configure)."""
        return self._trigger('configure')

    def trigger_cleanup(self) -> TransitionCallbackReturn:
        """inactive → unconfigured (via on_cleanup)."""
        return self._trigger('cleanup')

    def trigger_activate(self) -> TransitionCallbackReturn:
        """inactive → active (via on_activate)."""
        return self._trigger('activate')

    def trigger_deactivate(self) -> TransitionCallbackReturn:
        """active → inactive (via on_deactivate)."""
        return self._trigger('deactivate')

    def trigger_shutdown(self) -> TransitionCallbackReturn:
        """unconfigured, inactive or active → finalized (via on_shutdown)."""
        return self._trigger('shutdown')

    # -- default callbacks (rclpy's) --------------------------------------------------------------
    def on_configure(self, state: LifecycleState) -> TransitionCallbackReturn:
        """Entering `configuring`; SUCCESS leads to inactive."""
        return TransitionCallbackReturn.SUCCESS

    def on_cleanup(self, state: LifecycleState) -> TransitionCallbackReturn:
        """Entering `cleaningup`; SUCCESS leads to unconfigured."""
        return TransitionCallbackReturn.SUCCESS

    def on_shutdown(self, state: LifecycleState) -> TransitionCallbackReturn:
        """Entering `shuttingdown`; leads to finalized."""
        return TransitionCallbackReturn.SUCCESS

    def on_activate(self, state: LifecycleState) -> TransitionCallbackReturn:
        """Entering `activating`: activates every managed entity (call it when overriding)."""
        for entity in self._managed_entities:
            entity.on_activate(state)
        return TransitionCallbackReturn.SUCCESS

    def on_deactivate(self, state: LifecycleState) -> TransitionCallbackReturn:
        """Entering `deactivating`: deactivates every managed entity (call it when
        overriding)."""
        for entity in self._managed_entities:
            entity.on_deactivate(state)
        return TransitionCallbackReturn.SUCCESS

    def on_error(self, state: LifecycleState) -> TransitionCallbackReturn:
        """Entering `errorprocessing`; SUCCESS recovers to unconfigured, anything else
        finalizes."""
        return TransitionCallbackReturn.SUCCESS

    # -- the machinery --------------------------------------------------------------------------
    def _trigger(self, label: str) -> TransitionCallbackReturn:
        with self._transition_lock:
            return self._change_state(self._state_machine.transition_by_label(label))

    def _change_state(self, transition: TransitionDef) -> TransitionCallbackReturn:
        """Take `transition`, run its callback and follow the result (see the module doc)."""
        with self._transition_lock:
            previous = self.current_state
            self._take(transition)
            result = self._run_callback(self._state_machine.current, previous)
            self._take(self._state_machine.transition_by_label(result.to_label()))
            if result == TransitionCallbackReturn.ERROR:
                recovered = self._run_callback(ERRORPROCESSING, previous)
                self._take(self._state_machine.transition_by_label(recovered.to_label()))
            return result

    def _take(self, transition: TransitionDef) -> None:
        self._state_machine.take(transition)
        if self._transition_event_pub is not None:
            self._transition_event_pub.publish(
                _msg('msg/TransitionEvent')(
                    start_state=_state_msg(transition.start),
                    goal_state=_state_msg(transition.goal),
                )
            )

    def _run_callback(self, state_id: int, previous: LifecycleState) -> TransitionCallbackReturn:
        """The callback's answer; an exception or a wrong answer counts as ERROR."""
        callback = self._callbacks[state_id]
        logger = self.get_logger()  # type: ignore[attr-defined]
        try:
            result = callback(previous)
        except Exception as e:
            logger.error(
                f"exception in the callback for '{STATES[state_id]}': {type(e).__name__}: {e}"
            )
            return TransitionCallbackReturn.ERROR
        if not isinstance(result, TransitionCallbackReturn):
            logger.error(
                f"the callback for '{STATES[state_id]}' returned {result!r}, not a "
                'TransitionCallbackReturn'
            )
            return TransitionCallbackReturn.ERROR
        return result

    # -- the services ---------------------------------------------------------------------------
    def _on_change_state(
        self, request: lc_srv.ChangeState.Request, response: lc_srv.ChangeState.Response
    ) -> lc_srv.ChangeState.Response:
        requested = request.transition
        logger = self.get_logger()  # type: ignore[attr-defined]
        with self._transition_lock:
            try:
                if requested.label:
                    transition = self._state_machine.transition_by_label(requested.label)
                else:
                    transition = self._state_machine.transition_by_id(requested.id)
            except InvalidTransitionError as e:
                logger.warn(f'refused change_state request: {e}')
                response.success = False
                return response
            result = self._change_state(transition)
        response.success = result == TransitionCallbackReturn.SUCCESS
        return response


def _query(field: str, value: Callable[[], object]) -> Callable[[object, _Response], _Response]:
    """The callback of a service that only reads: its response's `field` set to `value()`."""

    def answer(request: object, response: _Response) -> _Response:
        setattr(response, field, value())
        return response

    return answer


def _state_msg(state_id: int) -> lc_msg.State:
    state: lc_msg.State = _msg('msg/State')(id=state_id, label=STATES[state_id])
    return state


def _description(t: TransitionDef) -> lc_msg.TransitionDescription:
    description: lc_msg.TransitionDescription = _msg('msg/TransitionDescription')(
        transition=_msg('msg/Transition')(id=t.id, label=t.label),
        start_state=_state_msg(t.start),
        goal_state=_state_msg(t.goal),
    )
    return description


class LifecycleNode(LifecycleNodeMixin, Node):
    """A managed node: a :class:`ros2lite.node.Node` with the lifecycle state machine.

    `enable_communication_interface=False` leaves out the services and the transition
    events (the node is then driven only by `trigger_*()` calls)."""

    def __init__(
        self,
        node_name: str,
        *,
        enable_communication_interface: bool = True,
        **kwargs: Unpack[NodeOptions],
    ) -> None:
        if not isinstance(enable_communication_interface, bool):
            raise TypeError('enable_communication_interface must be a bool')
        Node.__init__(self, node_name, **kwargs)
        LifecycleNodeMixin.__init__(
            self, enable_communication_interface=enable_communication_interface
        )
