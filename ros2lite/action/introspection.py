"""What `action echo` watches: an action's five interfaces as topics to subscribe to.

The three services are seen through their introspection events (the server or client must
have `configure_introspection` on, see :mod:`ros2lite.service_introspection`); feedback
and status are plain topics. Names, types and QoS follow Kilted's `ros2 action echo`.
"""

from __future__ import annotations

from dataclasses import dataclass

from ros2lite.action.goals import ActionNames
from ros2lite.qos import QoSProfile, qos_profile_action_status_default, qos_profile_services_default
from ros2lite.service_introspection import event_topic

__all__ = ['INTERFACES', 'WatchedInterface', 'action_interfaces']

INTERFACES = ('GOAL_SERVICE', 'CANCEL_SERVICE', 'RESULT_SERVICE', 'FEEDBACK_TOPIC', 'STATUS_TOPIC')


@dataclass(frozen=True)
class WatchedInterface:
    """One of an action's interfaces as `action echo` subscribes to it."""

    interface: str  # one of INTERFACES
    topic: str
    type_name: str
    qos: QoSProfile


def action_interfaces(action_name: str, action_type: str) -> list[WatchedInterface]:
    """The five interfaces of the (fully qualified) action `action_name`, in INTERFACES'
    order; `action_type` is `pkg/action/Name`."""
    topic_qos = {
        'FEEDBACK_TOPIC': QoSProfile(depth=10),
        'STATUS_TOPIC': qos_profile_action_status_default,
    }
    watched = []
    entities = ActionNames(action_name, action_type).entities()
    for interface, (role, name, type_name) in zip(INTERFACES, entities, strict=True):
        if role == 'service':
            watched.append(
                WatchedInterface(
                    interface, event_topic(name), f'{type_name}_Event', qos_profile_services_default
                )
            )
        else:
            watched.append(WatchedInterface(interface, name, type_name, topic_qos[interface]))
    return watched
