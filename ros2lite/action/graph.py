"""rclpy.action.graph: actions in the graph as a node sees them."""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from ros2lite.node import Node


def get_action_names_and_types(node: Node) -> list[tuple[str, list[str]]]:
    """Every action with a server or a client, with its type(s)."""
    from ros2lite.graph import action_names_and_types

    return action_names_and_types(node.context.graph.entities(), include_hidden=True)


def _by_node(
    node: Node, remote_node_name: str, remote_node_namespace: str, servers: bool
) -> list[tuple[str, list[str]]]:
    from ros2lite.graph import node_info

    info = node_info(
        node.context.graph.entities(), remote_node_name, remote_node_namespace, include_hidden=True
    )
    if info is None:
        return []
    return info.action_servers if servers else info.action_clients


def get_action_server_names_and_types_by_node(
    node: Node, remote_node_name: str, remote_node_namespace: str
) -> list[tuple[str, list[str]]]:
    """(action, types) that node serves."""
    return _by_node(node, remote_node_name, remote_node_namespace, True)


def get_action_client_names_and_types_by_node(
    node: Node, remote_node_name: str, remote_node_namespace: str
) -> list[tuple[str, list[str]]]:
    """(action, types) that node has clients of."""
    return _by_node(node, remote_node_name, remote_node_namespace, False)
