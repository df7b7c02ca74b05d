"""What the `lifecycle` verbs share: finding managed nodes and ros2cli's messages."""

from __future__ import annotations

from typing import TYPE_CHECKING

from ..errors import CliError

if TYPE_CHECKING:
    from ros2lite.tools.connection import Connection

NODE_NOT_FOUND = 'Node not found'


def absolute(node_name: str) -> str:
    """ros2cli's get_absolute_node_name: a relative name is taken from the root."""
    return node_name if node_name.startswith('/') else '/' + node_name


def managed_nodes(conn: Connection, include_hidden: bool) -> list[str]:
    """Full names of the managed nodes in the graph."""
    from ros2lite.lifecycle.remote import lifecycle_node_names

    return lifecycle_node_names(conn.entities(), include_hidden=include_hidden)


def require_node(conn: Connection, node_name: str, include_hidden: bool) -> str:
    """`node_name` made absolute, or 'Node not found' (exit 1) when it is no managed node."""
    full = absolute(node_name)
    if full not in managed_nodes(conn, include_hidden):
        raise CliError(NODE_NOT_FOUND)
    return full


def call_failed(node_name: str, error: Exception) -> str:
    """ros2cli's line for a lifecycle service call that raised."""
    return f"Exception while calling service of node '{node_name}': {error}"
