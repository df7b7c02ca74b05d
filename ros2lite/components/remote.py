"""Talking to component containers on the graph, as `ros2 component` does.

Any container that serves composition_interfaces' three services is one — ros2lite's or
`rclcpp_components`' on rmw_zenoh — so these calls drive real C++ containers too.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Iterable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from ros2lite.client import ServiceCallError
from ros2lite.exceptions import Ros2liteError
from ros2lite.graph import Entity, EntityKind
from ros2lite.names import node_fqn
from ros2lite.node import Node
from ros2lite.parameter import get_parameter_value

if TYPE_CHECKING:
    from ros2lite.msgs.rcl_interfaces.msg import Parameter as ParameterMsg

__all__ = [
    'ContainerError',
    'LoadedNode',
    'RemoteContainer',
    'container_node_names',
    'parse_assignments',
    'wait_for_container',
]

CONTAINER_SERVICES = {
    '_container/load_node': 'composition_interfaces/srv/LoadNode',
    '_container/unload_node': 'composition_interfaces/srv/UnloadNode',
    '_container/list_nodes': 'composition_interfaces/srv/ListNodes',
}
LIST_TIMEOUT = 5.0  # how long ros2cli waits for a container's list of components


class ContainerError(Ros2liteError):
    """A container refused a request or could not be reached; the message says why."""


@dataclass(frozen=True)
class LoadedNode:
    """One component in a container: its unique id and full node name."""

    unique_id: int
    name: str


def container_node_names(entities: Iterable[Entity]) -> list[str]:
    """Full names of the nodes serving all three container services, sorted."""
    offered: dict[str, set[str]] = {}
    for e in entities:
        if e.kind != EntityKind.SERVICE or not e.topic_name:
            continue
        for suffix, type_name in CONTAINER_SERVICES.items():
            if e.topic_name.endswith(suffix) and e.type_name == type_name:
                offered.setdefault(node_fqn(e.namespace, e.node_name), set()).add(suffix)
    return sorted(name for name, found in offered.items() if len(found) == len(CONTAINER_SERVICES))


def parse_assignments(items: Iterable[str]) -> list[ParameterMsg]:
    """'name:=value' strings as rcl_interfaces/msg/Parameter messages, values typed the
    YAML way (what `ros2 component load -p/-e` sends)."""
    from ros2lite.interfaces import get_interface

    param: type[ParameterMsg] = get_interface('rcl_interfaces/msg/Parameter')
    result = []
    for item in items:
        name, sep, value = item.partition(':=')
        if not sep or not name:
            raise ContainerError(f"'{item}' is not in the 'name:=value' form")
        result.append(param(name=name, value=get_parameter_value(value)))
    return result


class RemoteContainer:
    """The container node `target` (a full name), called from `node`. Calls block until
    the answer (at most `timeout` s, if given); the caller makes sure the container is there
    (:func:`container_node_names`): a call to a missing one fails at once."""

    def __init__(self, node: Node, target: str, timeout: float | None = None) -> None:
        self.node = node
        self.target = target
        self.timeout = timeout

    def _call(self, service: str, **fields: object) -> Any:  # the response of `service`
        from ros2lite.interfaces import get_interface

        srv = get_interface(CONTAINER_SERVICES[service])
        client = self.node.create_client(srv, f'{self.target}/{service}')
        try:
            return client.call(srv.Request(**fields), timeout_sec=self.timeout)
        except (ServiceCallError, TimeoutError) as e:
            raise ContainerError(f"'{self.target}' did not answer: {e}") from None
        finally:
            self.node.destroy_client(client)

    def list_nodes(self) -> list[LoadedNode]:
        """The components loaded in the container."""
        response = self._call('_container/list_nodes')
        return [
            LoadedNode(int(uid), name)
            for uid, name in zip(response.unique_ids, response.full_node_names, strict=False)
        ]

    def load(
        self,
        package: str,
        plugin: str,
        *,
        node_name: str | None = None,
        node_namespace: str | None = None,
        log_level: int = 0,
        remap_rules: list[str] | None = None,
        parameters: list[ParameterMsg] | None = None,
        extra_arguments: list[ParameterMsg] | None = None,
    ) -> LoadedNode:
        """Load a component; ContainerError('Failed to load component: …') if refused."""
        response = self._call(
            '_container/load_node',
            package_name=package,
            plugin_name=plugin,
            node_name=node_name or '',
            node_namespace=node_namespace or '',
            log_level=log_level,
            remap_rules=list(remap_rules or []),
            parameters=list(parameters or []),
            extra_arguments=list(extra_arguments or []),
        )
        if not response.success:
            reason = response.error_message
            raise ContainerError('Failed to load component: ' + reason[:1].upper() + reason[1:])
        return LoadedNode(int(response.unique_id), response.full_node_name)

    def unload(self, unique_id: int) -> str | None:
        """Unload one component; the container's reason when it refused, else None."""
        response = self._call('_container/unload_node', unique_id=unique_id)
        return None if response.success else str(response.error_message)


def wait_for_container(
    entities: Callable[[], list[Entity]],
    name: str,
    timeout: float,
    alive: Callable[[], bool] = lambda: True,
) -> bool:
    """Poll the graph until `name` serves the container services; False when `timeout` s
    pass or `alive()` turns False first (the container process died)."""
    deadline = time.monotonic() + timeout
    while alive():
        if name in container_node_names(entities()):
            return True
        if time.monotonic() >= deadline:
            return False
        time.sleep(0.05)
    return False
