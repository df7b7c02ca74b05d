"""Events of publishers and subscriptions (rclpy's `event_handler`): matched, incompatible QoS
and incompatible type, the events rmw_zenoh_cpp reports.

They come from the live graph, as rmw_zenoh's do: when an endpoint of the other side appears
on (or leaves) the topic, each handler of ours updates its counts and the executor runs its
callback with an info record, in the handler's callback group. Matched means what rmw_zenoh's
graph cache counts: the other side's endpoints of the same topic name and type, whatever their
QoS; so, as on rmw_zenoh, an incompatible-QoS handler can be made but never fires. By default
every publisher and subscription has the incompatible-QoS and incompatible-type handlers, which
log a warning; the type one fires when a type name or hash differs (no sample crosses then).
Deadline, liveliness and message-lost events have no source on rmw_zenoh (rmw_zenoh_cpp does
not offer them either): asking for one raises UnsupportedEventTypeError.
"""

from __future__ import annotations

import enum
import threading
from collections.abc import Callable
from typing import TYPE_CHECKING, NamedTuple

from ros2lite import logging
from ros2lite.exceptions import Ros2liteError
from ros2lite.graph import matches
from ros2lite.qos import QoSPolicyKind
from ros2lite.runtime.executable import Executable
from ros2lite.transport.keys import EntityKind

if TYPE_CHECKING:
    from ros2lite.callback_groups import CallbackGroup
    from ros2lite.graph import Entity, GraphCache
    from ros2lite.runtime.endpoint import EndpointOwner
    from ros2lite.task import Task

__all__ = [
    'EventHandler',
    'IncompatibleTypeInfo',
    'PublisherEventCallbacks',
    'QoSLivelinessChangedInfo',
    'QoSLivelinessLostInfo',
    'QoSMessageLostInfo',
    'QoSOfferedDeadlineMissedInfo',
    'QoSOfferedIncompatibleQoSInfo',
    'QoSPublisherEventType',
    'QoSPublisherMatchedInfo',
    'QoSRequestedDeadlineMissedInfo',
    'QoSRequestedIncompatibleQoSInfo',
    'QoSSubscriptionEventType',
    'QoSSubscriptionMatchedInfo',
    'SubscriptionEventCallbacks',
    'UnsupportedEventTypeError',
]


class UnsupportedEventTypeError(Ros2liteError, RuntimeError):
    """The event has no source here (rmw_zenoh reports no deadline or liveliness events)."""


class QoSPublisherEventType(enum.IntEnum):
    """A publisher's events (rcl's numbers)."""

    RCL_PUBLISHER_OFFERED_DEADLINE_MISSED = 0
    RCL_PUBLISHER_LIVELINESS_LOST = 1
    RCL_PUBLISHER_OFFERED_INCOMPATIBLE_QOS = 2
    RCL_PUBLISHER_INCOMPATIBLE_TYPE = 3
    RCL_PUBLISHER_MATCHED = 4


class QoSSubscriptionEventType(enum.IntEnum):
    """A subscription's events (rcl's numbers)."""

    RCL_SUBSCRIPTION_REQUESTED_DEADLINE_MISSED = 0
    RCL_SUBSCRIPTION_LIVELINESS_CHANGED = 1
    RCL_SUBSCRIPTION_REQUESTED_INCOMPATIBLE_QOS = 2
    RCL_SUBSCRIPTION_MESSAGE_LOST = 3
    RCL_SUBSCRIPTION_INCOMPATIBLE_TYPE = 4
    RCL_SUBSCRIPTION_MATCHED = 5


class QoSOfferedDeadlineMissedInfo(NamedTuple):
    """rclpy's record of missed publisher deadlines (never reported on rmw_zenoh)."""

    total_count: int
    total_count_change: int


class QoSRequestedDeadlineMissedInfo(NamedTuple):
    """rclpy's record of missed subscription deadlines (never reported on rmw_zenoh)."""

    total_count: int
    total_count_change: int


class QoSLivelinessLostInfo(NamedTuple):
    """rclpy's record of lost publisher liveliness (never reported on rmw_zenoh)."""

    total_count: int
    total_count_change: int


class QoSLivelinessChangedInfo(NamedTuple):
    """rclpy's record of publishers' liveliness changes (never reported on rmw_zenoh)."""

    alive_count: int
    not_alive_count: int
    alive_count_change: int
    not_alive_count_change: int


class QoSMessageLostInfo(NamedTuple):
    """rclpy's record of lost messages (never reported on rmw_zenoh)."""

    total_count: int
    total_count_change: int


class QoSOfferedIncompatibleQoSInfo(NamedTuple):
    """Subscriptions that asked a publisher for QoS it does not offer, and the last policy."""

    total_count: int
    total_count_change: int
    last_policy_kind: QoSPolicyKind


class QoSRequestedIncompatibleQoSInfo(NamedTuple):
    """Publishers that do not offer what a subscription asks for, and the last policy."""

    total_count: int
    total_count_change: int
    last_policy_kind: QoSPolicyKind


class IncompatibleTypeInfo(NamedTuple):
    """Endpoints on the topic with another type (or type hash)."""

    total_count: int
    total_count_change: int


class QoSPublisherMatchedInfo(NamedTuple):
    """Subscriptions a publisher matched, in total and now, with the changes since last."""

    total_count: int
    total_count_change: int
    current_count: int
    current_count_change: int


class QoSSubscriptionMatchedInfo(NamedTuple):
    """Publishers a subscription matched, in total and now, with the changes since last."""

    total_count: int
    total_count_change: int
    current_count: int
    current_count_change: int


# what an event handler gives its callback
EventInfo = (
    QoSPublisherMatchedInfo
    | QoSSubscriptionMatchedInfo
    | IncompatibleTypeInfo
    | QoSOfferedIncompatibleQoSInfo
    | QoSRequestedIncompatibleQoSInfo
)
# a user's callback takes one kind of info; the handler hands it the kind it asked for
EventCallback = Callable[..., object]


class _Kind(enum.Enum):
    MATCHED = 'matched'
    INCOMPATIBLE_QOS = 'incompatible_qos'
    INCOMPATIBLE_TYPE = 'incompatible_type'


# keyed by rcl's numbers (the enums are ints)
_PUBLISHER_EVENTS: dict[int, _Kind] = {
    QoSPublisherEventType.RCL_PUBLISHER_MATCHED: _Kind.MATCHED,
    QoSPublisherEventType.RCL_PUBLISHER_OFFERED_INCOMPATIBLE_QOS: _Kind.INCOMPATIBLE_QOS,
    QoSPublisherEventType.RCL_PUBLISHER_INCOMPATIBLE_TYPE: _Kind.INCOMPATIBLE_TYPE,
}
_SUBSCRIPTION_EVENTS: dict[int, _Kind] = {
    QoSSubscriptionEventType.RCL_SUBSCRIPTION_MATCHED: _Kind.MATCHED,
    QoSSubscriptionEventType.RCL_SUBSCRIPTION_REQUESTED_INCOMPATIBLE_QOS: _Kind.INCOMPATIBLE_QOS,
    QoSSubscriptionEventType.RCL_SUBSCRIPTION_INCOMPATIBLE_TYPE: _Kind.INCOMPATIBLE_TYPE,
}


class EventHandler(Executable):
    """One event of one publisher or subscription; `callback(info)` runs on the executor."""

    notifies_itself = True  # every change that readies it calls _notify()

    def __init__(
        self,
        *,
        callback_group: CallbackGroup | None,
        callback: EventCallback,
        event_type: QoSPublisherEventType | QoSSubscriptionEventType,
        parent: EndpointOwner,
    ) -> None:
        events = _PUBLISHER_EVENTS if _is_publisher(parent) else _SUBSCRIPTION_EVENTS
        kind = events.get(event_type)
        if kind is None:
            raise UnsupportedEventTypeError(
                f'{event_type.name}: rmw_zenoh reports no such event (only matched, '
                'incompatible QoS and incompatible type)'
            )
        node = parent.endpoint.node
        super().__init__(node, callback_group)
        self.callback = callback
        self.event_type = event_type
        self._kind = kind
        self._parent = parent
        self._lock = threading.Lock()
        self._matched: set[str] = set()
        self._total = 0
        self._total_change = 0
        self._current_change = 0
        self._last_policy = QoSPolicyKind.INVALID
        self._ready = False
        self._graph: GraphCache = node.context.graph
        for entity in self._graph.add_listener(self._on_graph):
            self._on_graph(entity, True)

    # -- from the graph (any thread) -------------------------------------------------------
    def _on_graph(self, entity: Entity, alive: bool) -> None:
        ep = self._parent.endpoint
        other = EntityKind.SUBSCRIPTION if ep.kind == EntityKind.PUBLISHER else EntityKind.PUBLISHER
        if entity.kind != other or entity.topic_name != ep.topic_name:
            return
        if self._kind is _Kind.INCOMPATIBLE_QOS:
            return  # rmw_zenoh's rule: no QoS pair is incompatible (see graph.matches)
        key = entity.to_token()
        with self._lock:
            if self._kind is _Kind.MATCHED:
                if not matches(entity, ep.topic_name, ep.type_name, other):
                    return
                if alive and key not in self._matched:
                    self._matched.add(key)
                    self._total += 1
                    self._total_change += 1
                    self._current_change += 1
                elif not alive and key in self._matched:
                    self._matched.discard(key)
                    self._current_change -= 1
                else:
                    return
            elif not alive:
                return
            else:  # incompatible type: data keys differ, so no sample crosses
                if entity.type_name == ep.type_name and entity.type_hash == ep.type_hash:
                    return
                self._total += 1
                self._total_change += 1
            self._ready = True
        self._notify()

    # -- the executor ------------------------------------------------------------------------
    def has_work(self) -> bool:
        return self._ready

    def run_pending(self, batch: bool, stop: Callable[[], bool] | None) -> Task | None:
        if not self._ready:
            return None
        return self._call(self.callback, self.take_event())

    def take_event(self) -> EventInfo:
        """The counts now, with the changes since the last take (which are then reset)."""
        publisher = _is_publisher(self._parent)
        with self._lock:
            self._ready = False
            total, change = self._total, self._total_change
            current, current_change = len(self._matched), self._current_change
            self._total_change = self._current_change = 0
        if self._kind is _Kind.MATCHED:
            matched = QoSPublisherMatchedInfo if publisher else QoSSubscriptionMatchedInfo
            return matched(total, change, current, current_change)
        if self._kind is _Kind.INCOMPATIBLE_TYPE:
            return IncompatibleTypeInfo(total, change)
        incompatible = (
            QoSOfferedIncompatibleQoSInfo if publisher else QoSRequestedIncompatibleQoSInfo
        )
        return incompatible(total, change, self._last_policy)

    def destroy(self) -> None:
        """Stop following the graph and leave the node's waitables."""
        self._graph.remove_listener(self._on_graph)
        if self._node is not None:
            self._node.remove_waitable(self)


def _is_publisher(parent: EndpointOwner) -> bool:
    return bool(parent.endpoint.kind == EntityKind.PUBLISHER)


class _EventCallbacks:
    """What publishers and subscription callbacks share."""

    _names: dict[str, QoSPublisherEventType] | dict[str, QoSSubscriptionEventType]

    def __init__(self, use_default_callbacks: bool) -> None:
        self.use_default_callbacks = use_default_callbacks

    def create_event_handlers(
        self, callback_group: CallbackGroup | None, parent: EndpointOwner, topic_name: str
    ) -> list[EventHandler]:
        """The handlers of `parent` (a publisher or subscription), defaults included."""
        handlers = []
        for attribute, event_type in self._names.items():
            callback: EventCallback | None = getattr(self, attribute)
            if callback is None:
                default = _DEFAULTS.get(attribute) if self.use_default_callbacks else None
                if default is None:
                    continue
                callback = default(parent, topic_name)
            handlers.append(
                EventHandler(
                    callback_group=callback_group,
                    callback=callback,
                    event_type=event_type,
                    parent=parent,
                )
            )
        return handlers


class PublisherEventCallbacks(_EventCallbacks):
    """The callbacks a publisher wants for its events (rclpy's names)."""

    _names = {
        'deadline': QoSPublisherEventType.RCL_PUBLISHER_OFFERED_DEADLINE_MISSED,
        'incompatible_qos': QoSPublisherEventType.RCL_PUBLISHER_OFFERED_INCOMPATIBLE_QOS,
        'liveliness': QoSPublisherEventType.RCL_PUBLISHER_LIVELINESS_LOST,
        'incompatible_type': QoSPublisherEventType.RCL_PUBLISHER_INCOMPATIBLE_TYPE,
        'matched': QoSPublisherEventType.RCL_PUBLISHER_MATCHED,
    }

    def __init__(
        self,
        *,
        deadline: Callable[[QoSOfferedDeadlineMissedInfo], object] | None = None,
        incompatible_qos: Callable[[QoSOfferedIncompatibleQoSInfo], object] | None = None,
        liveliness: Callable[[QoSLivelinessLostInfo], object] | None = None,
        incompatible_type: Callable[[IncompatibleTypeInfo], object] | None = None,
        matched: Callable[[QoSPublisherMatchedInfo], object] | None = None,
        use_default_callbacks: bool = True,
    ) -> None:
        super().__init__(use_default_callbacks)
        self.deadline = deadline
        self.incompatible_qos = incompatible_qos
        self.liveliness = liveliness
        self.incompatible_type = incompatible_type
        self.matched = matched


class SubscriptionEventCallbacks(_EventCallbacks):
    """The callbacks a subscription wants for its events (rclpy's names)."""

    _names = {
        'deadline': QoSSubscriptionEventType.RCL_SUBSCRIPTION_REQUESTED_DEADLINE_MISSED,
        'incompatible_qos': QoSSubscriptionEventType.RCL_SUBSCRIPTION_REQUESTED_INCOMPATIBLE_QOS,
        'liveliness': QoSSubscriptionEventType.RCL_SUBSCRIPTION_LIVELINESS_CHANGED,
        'message_lost': QoSSubscriptionEventType.RCL_SUBSCRIPTION_MESSAGE_LOST,
        'incompatible_type': QoSSubscriptionEventType.RCL_SUBSCRIPTION_INCOMPATIBLE_TYPE,
        'matched': QoSSubscriptionEventType.RCL_SUBSCRIPTION_MATCHED,
    }

    def __init__(
        self,
        *,
        deadline: Callable[[QoSRequestedDeadlineMissedInfo], object] | None = None,
        incompatible_qos: Callable[[QoSRequestedIncompatibleQoSInfo], object] | None = None,
        liveliness: Callable[[QoSLivelinessChangedInfo], object] | None = None,
        message_lost: Callable[[QoSMessageLostInfo], object] | None = None,
        incompatible_type: Callable[[IncompatibleTypeInfo], object] | None = None,
        matched: Callable[[QoSSubscriptionMatchedInfo], object] | None = None,
        use_default_callbacks: bool = True,
    ) -> None:
        super().__init__(use_default_callbacks)
        self.deadline = deadline
        self.incompatible_qos = incompatible_qos
        self.liveliness = liveliness
        self.message_lost = message_lost
        self.incompatible_type = incompatible_type
        self.matched = matched


# -- the default callbacks: a warning, as rclpy logs it --------------------------------------


def _warn(message: str) -> None:

    logging.get_logger('rclpy.qos_event').warn(message)


def _incompatible_qos_warning(
    parent: EndpointOwner, topic_name: str
) -> Callable[[QoSOfferedIncompatibleQoSInfo | QoSRequestedIncompatibleQoSInfo], None]:
    if _is_publisher(parent):
        text = (
            f"New subscription discovered on topic '{topic_name}', requesting incompatible QoS. "
            'No messages will be sent to it. Last incompatible policy: {}'
        )
    else:
        text = (
            f"New publisher discovered on topic '{topic_name}', offering incompatible QoS. "
            'No messages will be received from it. Last incompatible policy: {}'
        )
    return lambda info: _warn(text.format(info.last_policy_kind.name))


def _incompatible_type_warning(
    parent: EndpointOwner, topic_name: str
) -> Callable[[IncompatibleTypeInfo], None]:
    side = 'subscription' if _is_publisher(parent) else 'publisher'
    return lambda info: _warn(
        f"Incompatible type on topic '{topic_name}', no messages will be sent to it "
        f'(a {side} of another type or type hash appeared)'
    )


_DEFAULTS: dict[str, Callable[[EndpointOwner, str], EventCallback]] = {
    'incompatible_qos': _incompatible_qos_warning,
    'incompatible_type': _incompatible_type_warning,
}
