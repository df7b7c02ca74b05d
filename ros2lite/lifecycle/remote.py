"""Driving another node's lifecycle through its services, as `ros2 lifecycle` does.

Works with any managed node on the graph — ours or a C++/rclpy one on rmw_zenoh — because it
speaks only lifecycle_msgs over the standard `<node>/get_state`, `get_available_transitions`,
`get_transition_graph` and `change_state` services.
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import TYPE_CHECKING, Any

from ros2lite.graph import Entity, EntityKind
from ros2lite.lifecycle.state_machine import LifecycleState, TransitionDef
from ros2lite.names import node_fqn
from ros2lite.node import Node

if TYPE_CHECKING:
    from ros2lite.client import Client
    from ros2lite.interfaces import Message
    from ros2lite.msgs.lifecycle_msgs.msg import State, TransitionDescription

__all__ = ['RemoteLifecycle', 'has_lifecycle', 'lifecycle_node_names']

GET_STATE_TYPE = 'lifecycle_msgs/srv/GetState'


def lifecycle_node_names(entities: Iterable[Entity], *, include_hidden: bool = False) -> list[str]:
    """Full names of the nodes that serve `<node>/get_state` (lifecycle_msgs' GetState),
    sorted; a node is hidden when its own name starts with '_'."""
    found = {
        node_fqn(e.namespace, e.node_name)
        for e in entities
        if e.kind == EntityKind.SERVICE
        and e.type_name == GET_STATE_TYPE
        and e.topic_name == node_fqn(e.namespace, e.node_name) + '/get_state'
        and (include_hidden or not e.node_name.startswith('_'))
    }
    return sorted(found)


def has_lifecycle(entities: Iterable[Entity], node: str) -> bool:
    """Whether `node` (a full name) is a managed node in the graph, hidden or not."""
    return node in lifecycle_node_names(entities, include_hidden=True)


def _definition(description: TransitionDescription) -> TransitionDef:
    return TransitionDef(
        description.transition.id,
        description.transition.label,
        description.start_state.id,
        description.goal_state.id,
    )


class RemoteLifecycle:
    """The lifecycle services of the node `target` (a full name), called from `node`.

    Calls block the calling thread until the answer (or `timeout` s, then TimeoutError); a
    failed call raises :class:`ros2lite.client.ServiceCallError`. Labels of states come back
    as the node reports them, so :attr:`state_labels` names the ids seen so far."""

    def __init__(self, node: Node, target: str) -> None:
        self.node = node
        self.target = target.rstrip('/') or '/'
        self._clients: dict[str, Client[Message, Message]] = {}
        self.state_labels: dict[int, str] = {}

    def _call(
        self, service: str, type_name: str, timeout: float | None, **fields: object
    ) -> Any:  # the response of the lifecycle_msgs service `type_name`
        from ros2lite.interfaces import get_interface

        srv = get_interface(type_name)
        client = self._clients.get(service)
        if client is None:
            client = self.node.create_client(srv, f'{self.target}/{service}')
            self._clients[service] = client
        return client.call(srv.Request(**fields), timeout_sec=timeout)

    def _remember(self, state: State) -> None:
        self.state_labels[state.id] = state.label

    def get_state(self, timeout: float | None = None) -> LifecycleState:
        """The node's current state."""
        state = self._call('get_state', GET_STATE_TYPE, timeout).current_state
        self._remember(state)
        return LifecycleState(state.label, state.id)

    def _transitions(self, service: str, timeout: float | None) -> list[TransitionDef]:
        response = self._call(service, 'lifecycle_msgs/srv/GetAvailableTransitions', timeout)
        for d in response.available_transitions:
            self._remember(d.start_state)
            self._remember(d.goal_state)
        return [_definition(d) for d in response.available_transitions]

    def available_transitions(self, timeout: float | None = None) -> list[TransitionDef]:
        """The transitions the node offers from where it is now."""
        return self._transitions('get_available_transitions', timeout)

    def transition_graph(self, timeout: float | None = None) -> list[TransitionDef]:
        """Every transition of the node's state machine."""
        return self._transitions('get_transition_graph', timeout)

    def change_state(self, transition: TransitionDef, timeout: float | None = None) -> bool:
        """Ask the node to take `transition`; True when it reached the goal."""
        from ros2lite.interfaces import get_interface

        msg = get_interface('lifecycle_msgs/msg/Transition')(
            id=transition.id, label=transition.label
        )
        response = self._call(
            'change_state', 'lifecycle_msgs/srv/ChangeState', timeout, transition=msg
        )
        return bool(response.success)

    def close(self) -> None:
        """Destroy the clients (the node stays)."""
        for client in self._clients.values():
            self.node.destroy_client(client)
        self._clients.clear()
