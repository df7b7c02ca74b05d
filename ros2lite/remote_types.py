"""Types asked of the graph: when no local package defines the type of a topic, a service or
an action, a node that uses it is asked for it on its `~/get_type_description` service.

The graph names who uses a type and the RIHS01 hash each announces; the answer is checked
against that hash and installed in the process's registry by :mod:`ros2lite.interfaces.remote`,
after which codecs, classes, bag schemas and `interface show` see it as any local type. Used by
the CLI's type look-ups (echo, pub, service call, bag record, interface show) and the Foxglove
bridge.
"""

from __future__ import annotations

import sys
from collections.abc import Callable, Iterable
from typing import TYPE_CHECKING

from ros2lite.graph import Entity, EntityKind
from ros2lite.interfaces import get_interface
from ros2lite.interfaces.errors import InterfaceError
from ros2lite.interfaces.parser import validate_type_name
from ros2lite.interfaces.registry import default_registry, normalize_name
from ros2lite.interfaces.remote import RemoteTypeError, assemble_action, fetched_from, install

if TYPE_CHECKING:
    from ros2lite.node import Node

__all__ = ['RemoteTypeError', 'ensure_type', 'is_known', 'offering_nodes']

SERVICE_TYPE = 'type_description_interfaces/srv/GetTypeDescription'
# how long one node gets to answer: a description is one small service call
ANSWER_TIMEOUT = 5.0


def is_known(type_name: str) -> bool:
    """Whether the local search path (or an earlier fetch) defines the type."""
    try:
        default_registry().kind_of(normalize_name(type_name))
    except (InterfaceError, ValueError):
        return False
    return True


def _type_names(type_name: str) -> set[str]:
    """The names endpoints of a type announce: an action's are its services and topics."""
    if type_name.split('/')[1] != 'action' or '_' in type_name.rsplit('/', 1)[1]:
        return {type_name}
    return {type_name + s for s in ('_SendGoal', '_GetResult', '_FeedbackMessage')}


def offering_nodes(
    entities: Iterable[Entity], type_name: str, name: str | None = None
) -> list[tuple[str, str, str]]:
    """(node, announced type, its hash) of each endpoint using the type whose node serves
    `~/get_type_description` (a tool's hidden node does not): those on `name` (a topic or
    service) first, then publishers and servers, then the rest."""
    every = list(entities)
    describing = {
        e.topic_name for e in every if e.kind is EntityKind.SERVICE and e.type_name == SERVICE_TYPE
    }
    wanted = _type_names(type_name)
    out: dict[tuple[str, str, str], int] = {}
    for e in every:
        if e.is_node or e.type_name not in wanted or not e.type_hash:
            continue
        if f'{e.node_fqn.rstrip("/")}/get_type_description' not in describing:
            continue
        rank = (0 if e.topic_name == name else 2) + (
            0 if e.kind in (EntityKind.PUBLISHER, EntityKind.SERVICE) else 1
        )
        key = (e.node_fqn, e.type_name, e.type_hash)
        out[key] = min(rank, out.get(key, rank))
    return sorted(out, key=lambda k: (out[k], k))


def _ask(node: Node, fqn: str, type_name: str, type_hash: str, timeout: float) -> str | None:
    """Install the type from node `fqn`'s description; None, or why that node could not."""
    srv = get_interface(SERVICE_TYPE)
    client = node.create_client(srv, f'{fqn.rstrip("/")}/get_type_description')
    try:
        if not client.wait_for_service(timeout_sec=timeout):
            return f'{fqn} offers no ~/get_type_description'
        request = srv.Request(type_name=type_name, type_hash=type_hash, include_type_sources=True)
        response = client.call(request, timeout_sec=timeout)
    finally:
        node.destroy_client(client)
    if response is None:
        return f'{fqn} did not describe it within {timeout:g} s'
    if not response.successful:
        return f'{fqn} did not describe it: {response.failure_reason}'
    install(type_name, type_hash, response.type_description, response.type_sources, f'node {fqn}')
    return None


def ensure_type(
    node: Callable[[], Node],
    entities: Iterable[Entity],
    type_name: str,
    name: str | None = None,
    *,
    timeout: float = ANSWER_TIMEOUT,
    say: Callable[[str], object] | None = None,
) -> bool:
    """Make `type_name` known, fetching it from a node that uses it (on topic or service
    `name` if given) when the local search path lacks it (`node()` makes the asking node
    only then); True if it is known now, False if no node offers it. Saying where it came
    from goes to `say` (stderr by default). RemoteTypeError when every node asked failed:
    the first that described something that does not fit, else the first reason."""
    type_name = normalize_name(type_name)
    if is_known(type_name):
        return True
    try:
        validate_type_name(type_name)
    except InterfaceError:
        return False
    report = say or (lambda text: print(text, file=sys.stderr, flush=True))
    lie: RemoteTypeError | None = None
    failed: list[str] = []
    sources: list[str] = []  # the nodes that described (an action's parts may be several)
    for fqn, announced, type_hash in offering_nodes(entities, type_name, name):
        if fetched_from(announced, type_hash) is None:
            try:
                why = _ask(node(), fqn, announced, type_hash, timeout)
            except RemoteTypeError as e:
                lie = lie or e
                continue
            if why is not None:
                failed.append(why)
                continue
            if fqn not in sources:
                sources.append(fqn)
        if announced != type_name:
            assemble_action(type_name)
        if is_known(type_name):
            if sources:
                report(f'ros2lite: type {type_name} fetched from node {", ".join(sources)}')
            return True
    if lie is not None:
        raise lie
    if failed:
        raise RemoteTypeError(f'type {type_name} is not defined here, and {failed[0]}')
    return False
