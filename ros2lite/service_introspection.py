"""Service introspection, as rcl has it: clients and services report what they do.

Turned on per client or service with `configure_introspection(clock, qos, state)`, each
request and response becomes a `<Srv>_Event` message on `<service>/_service_event`: the
client publishes REQUEST_SENT and RESPONSE_RECEIVED, the service REQUEST_RECEIVED and
RESPONSE_SENT, each with the client's GID, the request's sequence number and a stamp of the
given clock; with CONTENTS the request or response itself rides along. `service echo` prints
them and `bag record --services` records them, for ros2lite's nodes and C++/rclpy ones alike.
"""

from __future__ import annotations

import enum
from typing import TYPE_CHECKING, Protocol, overload

from ros2lite.qos import QoSProfile
from ros2lite.runtime.executable import EntityNode

if TYPE_CHECKING:
    from ros2lite.clock import Clock
    from ros2lite.interfaces import Message
    from ros2lite.interfaces.convert import FormatOptions
    from ros2lite.publisher import Publisher
    from ros2lite.runtime.endpoint import Endpoint
    from ros2lite.type_support import Msg, MsgT

__all__ = [
    'EVENT_TOPIC_SUFFIX',
    'Introspectable',
    'IntrospectionMixin',
    'ServiceEventType',
    'ServiceIntrospectionState',
    'ServiceNode',
    'event_to_dict',
    'event_topic',
    'format_event',
    'state_from_name',
]


class ServiceNode(EntityNode, Protocol):
    """The node of a service or client (:class:`ros2lite.node.Node`): an entity's node that
    also makes the publisher of its introspection events, and stamps them with its clock."""

    @overload
    def create_publisher(
        self, msg_type: type[MsgT], topic: str, qos_profile: QoSProfile | int
    ) -> Publisher[MsgT]: ...

    @overload
    def create_publisher(
        self, msg_type: str, topic: str, qos_profile: QoSProfile | int
    ) -> Publisher[MsgT]: ...

    def create_publisher(
        self, msg_type: type[MsgT] | str, topic: str, qos_profile: QoSProfile | int
    ) -> Publisher[MsgT]:
        """A publisher of the node's, of a message class or a 'pkg/msg/Name'."""
        ...

    def destroy_publisher(self, pub: Publisher[MsgT]) -> bool:
        """Withdraw a publisher of the node's; False if it is not (or no longer) one."""
        ...

    def get_clock(self) -> Clock:
        """The node's ROS clock."""
        ...


EVENT_TOPIC_SUFFIX = '/_service_event'
GID_SIZE = 16  # service_msgs/msg/ServiceEventInfo's char[16] client_gid


class ServiceIntrospectionState(enum.IntEnum):
    """How much a client or service reports (rclpy's names)."""

    OFF = 0
    METADATA = 1  # who, when, which request: no message contents
    CONTENTS = 2  # the requests and responses too


class ServiceEventType(enum.IntEnum):
    """service_msgs/msg/ServiceEventInfo's event types."""

    REQUEST_SENT = 0
    REQUEST_RECEIVED = 1
    RESPONSE_SENT = 2
    RESPONSE_RECEIVED = 3


_EVENT_NAMES = {e.value: e.name for e in ServiceEventType}


# the words the introspection demos' parameters take
STATE_NAMES = {
    'disabled': ServiceIntrospectionState.OFF,
    'metadata': ServiceIntrospectionState.METADATA,
    'contents': ServiceIntrospectionState.CONTENTS,
}


def state_from_name(name: str) -> ServiceIntrospectionState:
    """'disabled', 'metadata' or 'contents' as a state; ValueError for anything else."""
    state = STATE_NAMES.get(name)
    if state is None:
        raise ValueError("must be one of 'disabled', 'metadata', or 'contents'")
    return state


def event_topic(service_name: str) -> str:
    """Where the events of the (fully qualified) service `service_name` are published."""
    return service_name.rstrip('/') + EVENT_TOPIC_SUFFIX


def event_to_dict(
    event: Message,
    *,
    truncate_length: int | None = None,
    no_arr: bool = False,
    no_str: bool = False,
) -> dict[str, object]:
    """A `<Srv>_Event` message as a dict, its event type by name (`REQUEST_SENT`…): what
    `service echo` prints."""
    from ros2lite.interfaces import message_to_dict

    data = message_to_dict(event, truncate_length=truncate_length, no_arr=no_arr, no_str=no_str)
    info = data.get('info')
    if isinstance(info, dict) and info.get('event_type') in _EVENT_NAMES:
        info['event_type'] = _EVENT_NAMES[info['event_type']]
    return data


def format_event(
    message: Message,
    *,
    csv: bool = False,
    flow_style: bool = False,
    truncate_length: int | None = None,
    no_arr: bool = False,
    no_str: bool = False,
) -> str:
    """An event (or any message) as `service echo`/`action echo` print it: YAML with the
    event type by name (ending in a newline), or one CSV line (without)."""
    from ros2lite.interfaces import message_to_csv
    from ros2lite.interfaces.convert import dict_to_yaml

    fmt: FormatOptions = {'truncate_length': truncate_length, 'no_arr': no_arr, 'no_str': no_str}
    if csv:
        return message_to_csv(message, **fmt)
    return dict_to_yaml(event_to_dict(message, **fmt), flow_style=flow_style)


class _EventPublisher:
    """The `_service_event` publisher of one client or service, and its settings."""

    def __init__(
        self, node: ServiceNode, type_name: str, service_name: str, qos: QoSProfile
    ) -> None:
        from ros2lite.interfaces import get_interface

        self.node = node
        self.event_class = get_interface(f'{type_name}_Event')
        self.info_class = get_interface('service_msgs/msg/ServiceEventInfo')
        self.publisher: Publisher = node.create_publisher(
            self.event_class, event_topic(service_name), qos
        )
        self.clock: Clock | None = None
        self.contents = False

    def publish(
        self,
        event_type: ServiceEventType,
        sequence_number: int,
        gid: bytes,
        message: Msg | None,
    ) -> None:
        """Publish one event (with `message` when the contents are reported)."""
        clock = self.clock if self.clock is not None else self.node.get_clock()
        gid16 = bytes(gid[:GID_SIZE]).ljust(GID_SIZE, b'\0')
        info = self.info_class(
            event_type=int(event_type),
            stamp=clock.now().to_msg(),
            client_gid=list(gid16),
            sequence_number=sequence_number,
        )
        event = self.event_class(info=info)
        if self.contents and message is not None:
            if event_type in (ServiceEventType.REQUEST_SENT, ServiceEventType.REQUEST_RECEIVED):
                event.request = [message]
            else:
                event.response = [message]
        self.publisher.publish(event)

    def destroy(self) -> None:
        self.node.destroy_publisher(self.publisher)  # unless the node destroyed it already


class Introspectable:
    """What reports service events when asked: a client or a service, or an action client
    or server (through its three service clients or services)."""

    def _introspected(self) -> tuple[IntrospectionMixin, ...]:
        """The clients or services whose events this one reports."""
        raise NotImplementedError

    def configure_introspection(
        self,
        clock: Clock,
        service_event_qos_profile: QoSProfile,
        introspection_state: ServiceIntrospectionState,
    ) -> None:
        """Report the events from now on (OFF: stop), on each service's `_service_event`
        topic (an action's: its three services', which is what `action echo` shows)."""
        state = ServiceIntrospectionState(introspection_state)
        for endpoint in self._introspected():
            endpoint.configure_introspection(clock, service_event_qos_profile, state)


class IntrospectionMixin(Introspectable):
    """What `Service` and `Client` share for introspection. The class using it provides
    `_node`, `srv_name` and `_ep` (whose `type_name` is the `pkg/srv/Name` of its type)."""

    _introspection: _EventPublisher | None = None
    _node: ServiceNode
    _ep: Endpoint
    srv_name: str

    @property
    def endpoint(self) -> Endpoint:
        """The graph endpoint it announces (names, type, QoS, node)."""
        return self._ep

    def configure_introspection(
        self,
        clock: Clock,
        service_event_qos_profile: QoSProfile,
        introspection_state: ServiceIntrospectionState,
    ) -> None:
        """Report this service's or client's events from now on (OFF: stop) on its
        `_service_event` topic."""
        qos = service_event_qos_profile
        state = ServiceIntrospectionState(introspection_state)
        if state == ServiceIntrospectionState.OFF:
            self._destroy_introspection()
            return
        if self._introspection is None:
            self._introspection = _EventPublisher(
                self._node, self._ep.type_name, self.srv_name, qos
            )
        self._introspection.clock = clock
        self._introspection.contents = state == ServiceIntrospectionState.CONTENTS

    def _introspect(
        self,
        event_type: ServiceEventType,
        sequence_number: int,
        gid: bytes,
        message: Msg | None,
    ) -> None:
        """Publish one event if introspection is on (any thread)."""
        events = self._introspection
        if events is not None:
            events.publish(event_type, sequence_number, gid, message)

    def _destroy_introspection(self) -> None:
        events, self._introspection = self._introspection, None
        if events is not None:
            events.destroy()
