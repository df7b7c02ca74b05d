"""The ROS graph as seen through rmw_zenoh liveliness tokens.

Two ways in: a live `GraphCache` that a node keeps up to date (like rmw_zenoh's graph cache), and
`snapshot()`, a one-shot liveliness query that returns once every token has answered — tools
use it when the daemon's graph cache (:mod:`ros2lite.daemon.graph_cache`) cannot answer, so
`topic list` needs no spin time and never misses a slow reply. Both, and the daemon's answers,
become entities through `parse_tokens`.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable, Iterable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Protocol

from ros2lite.names import absolute_node_name, action_entity_name, is_hidden_name, node_fqn
from ros2lite.topic_endpoint_info import TopicEndpointInfo, TopicEndpointTypeEnum, format_gid
from ros2lite.transport.keys import Entity, EntityKind, parse_token

if TYPE_CHECKING:
    from ros2lite.transport.handles import Session

# Entity and EntityKind are the graph's vocabulary; other modules import them from here
__all__ = [
    'Entity',
    'EntityKind',
    'GraphCache',
    'GraphContext',
    'GraphMixin',
    'GraphView',
    'NodeInfo',
    'TopicEndpointInfo',
    'action_endpoints',
    'action_names_and_types',
    'count',
    'endpoints_by_topic',
    'format_endpoint_info',
    'format_gid',
    'names_and_types_by_node',
    'node_full_names',
    'node_info',
    'node_names_and_namespaces',
    'parse_tokens',
    'read_tokens',
    'service_names_and_types',
    'snapshot',
    'survey',
    'topic_counts',
    'topic_names_and_types',
]

_TOPIC_KINDS = (EntityKind.PUBLISHER, EntityKind.SUBSCRIPTION)
# how long a node's graph cache waits for its first complete picture of the graph (s)
SEED_TIMEOUT = 0.5
_SERVICE_KINDS = (EntityKind.SERVICE, EntityKind.CLIENT)


def snapshot(session: Session, domain_id: int, timeout: float = 5.0) -> list[Entity]:
    """All entities in the domain, from one complete liveliness query."""
    return survey(session, domain_id, timeout).entities


@dataclass
class GraphView:
    """The entities of one look at the graph, with what a tool should say about it: the
    keys skipped as no token rmw_zenoh makes, and whether the answer was whole."""

    entities: list[Entity]
    skipped: list[str]
    complete: bool = True


def survey(session: Session, domain_id: int, timeout: float = 5.0) -> GraphView:
    """The domain's entities from one liveliness query, saying whether the time-out cut it."""
    from ros2lite.transport.session import liveliness_answer

    keys, complete = liveliness_answer(session, domain_id, timeout)
    return read_tokens(keys, complete=complete)


def read_tokens(keys: Iterable[str], *, complete: bool = True) -> GraphView:
    """`parse_tokens`, keeping the keys it skipped (each once) for the tool to report."""
    entities: list[Entity] = []
    skipped: list[str] = []
    for key in dict.fromkeys(keys):
        entity = parse_token(key)
        if entity is None:
            skipped.append(key)
        else:
            entities.append(entity)
    return GraphView(entities, skipped, complete)


def parse_tokens(keys: Iterable[str]) -> list[Entity]:
    """The entities of liveliness token keys (each once: a peer session may hear a token
    from its router and from the peer itself); keys that are no rmw_zenoh token are dropped."""
    return [e for e in map(parse_token, dict.fromkeys(keys)) if e is not None]


class GraphCache:
    """Entities kept current from a liveliness subscriber with history."""

    def __init__(self, session: Session, domain_id: int) -> None:
        from ros2lite.transport.session import declare_liveliness_subscriber

        self._entities: dict[str, Entity] = {}
        self._cond = threading.Condition()
        # seed synchronously (as rmw_zenoh does with a liveliness get) so the first query
        # after creation already sees the graph; the subscriber then keeps it current.  The
        # wait is bounded: a router busy with a token flood answers a first query slowly
        # (10k tokens: several seconds, upstream), and a node must not wait for all of it:
        # the subscriber's history brings the rest
        for entity in snapshot(session, domain_id, SEED_TIMEOUT):
            self._entities[entity.to_token()] = entity
        # called with (entity, alive) for each change, on the thread that saw it
        self._listeners: list[Callable[[Entity, bool], None]] = []
        self._sub = declare_liveliness_subscriber(session, domain_id, self.token_changed)

    def token_changed(self, key: str, alive: bool) -> None:
        """A liveliness token appeared or went (the subscriber's callback; the context
        tells its own entities' at once)."""
        with self._cond:
            if alive:
                if key in self._entities:
                    return  # known already (our own entities are added at once)
                entity = parse_token(key)
                if entity is None:
                    return
                self._entities[key] = entity
            else:
                gone = self._entities.pop(key, None)
                if gone is None:
                    return
                entity = gone
            self._cond.notify_all()
            listeners = list(self._listeners)
        for listener in listeners:
            listener(entity, alive)

    def add_listener(self, listener: Callable[[Entity, bool], None]) -> list[Entity]:
        """Call `listener(entity, alive)` on every later change; returns the entities now."""
        with self._cond:
            self._listeners.append(listener)
            return list(self._entities.values())

    def remove_listener(self, listener: Callable[[Entity, bool], None]) -> None:
        """Stop calling a listener given to :meth:`add_listener`."""
        with self._cond:
            if listener in self._listeners:
                self._listeners.remove(listener)

    def entities(self) -> list[Entity]:
        """Every entity on the graph now (a copy)."""
        with self._cond:
            return list(self._entities.values())

    def wait_for(self, predicate: Callable[[list[Entity]], bool], timeout: float | None) -> bool:
        """Block until `predicate(entities)` holds or the timeout passes."""
        deadline = None if timeout is None else time.monotonic() + timeout
        with self._cond:
            while not predicate(list(self._entities.values())):
                remaining = None if deadline is None else deadline - time.monotonic()
                if remaining is not None and remaining <= 0:
                    return False
                self._cond.wait(remaining if remaining is not None else 1.0)
        return True

    def close(self) -> None:
        """Stop following the graph."""
        from ros2lite.transport.session import undeclare_quietly

        undeclare_quietly(self._sub)


# -- queries over a list of entities (shared by GraphCache and snapshot users) -------------------


def node_names_and_namespaces(entities: Iterable[Entity]) -> list[tuple[str, str]]:
    """(name, namespace) of every node, once per node instance, in name order."""
    seen: dict[tuple[str, int], tuple[str, str]] = {}
    for e in entities:
        seen.setdefault((e.zid, e.nid), (e.node_name, e.namespace))
    return sorted(seen.values(), key=lambda nn: nn[1].rstrip('/') + '/' + nn[0])


def _names_and_types(
    entities: Iterable[Entity], kinds: tuple[EntityKind, ...]
) -> list[tuple[str, list[str]]]:
    table: dict[str, set[str]] = {}
    for e in entities:
        if e.kind in kinds and e.topic_name and e.type_name:
            table.setdefault(e.topic_name, set()).add(e.type_name)
    return [(name, sorted(types)) for name, types in sorted(table.items())]


def topic_names_and_types(
    entities: Iterable[Entity], include_hidden: bool = False
) -> list[tuple[str, list[str]]]:
    """(topic, types) of the graph's publishers and subscriptions, sorted."""
    result = _names_and_types(entities, _TOPIC_KINDS)
    return result if include_hidden else [r for r in result if not is_hidden_name(r[0])]


def service_names_and_types(
    entities: Iterable[Entity], include_hidden: bool = False
) -> list[tuple[str, list[str]]]:
    """(service, types) of the graph's servers and clients, sorted."""
    result = _names_and_types(entities, _SERVICE_KINDS)
    return result if include_hidden else [r for r in result if not is_hidden_name(r[0])]


def _of_node(entities: Iterable[Entity], node: str, namespace: str) -> list[Entity]:
    ns = namespace or '/'
    return [e for e in entities if e.node_name == node and e.namespace == ns]


def names_and_types_by_node(
    entities: Iterable[Entity], node: str, namespace: str, kind: EntityKind
) -> list[tuple[str, list[str]]]:
    """(name, types) of one node's entities of `kind`."""
    return _names_and_types(_of_node(entities, node, namespace), (kind,))


def endpoints_by_topic(
    entities: Iterable[Entity], topic: str, kind: EntityKind
) -> list[TopicEndpointInfo]:
    """Node, type, GID and QoS of each endpoint of `kind` on `topic`."""
    from ros2lite.transport.attachment import gid_from_token

    label = (
        TopicEndpointTypeEnum.PUBLISHER
        if kind == EntityKind.PUBLISHER
        else TopicEndpointTypeEnum.SUBSCRIPTION
    )
    return [
        TopicEndpointInfo(
            e.node_name,
            e.namespace,
            e.type_name or '',
            e.type_hash or '',
            label,
            gid_from_token(e.to_token()),
            e.qos,
        )
        for e in entities
        if e.kind == kind and e.topic_name == topic
    ]


def count(entities: Iterable[Entity], topic: str, kind: EntityKind) -> int:
    """How many entities of `kind` the graph has on `topic`."""
    return sum(1 for e in entities if e.kind == kind and e.topic_name == topic)


def matches(entity: Entity, topic: str, type_name: str | None, kind: EntityKind) -> bool:
    """Is `entity` a `kind` endpoint matched with ours on `topic` of `type_name`?

    rmw_zenoh's graph cache files endpoints by topic name, then type name, then QoS string,
    and counts as matched every endpoint of the other side under the same name and type
    whatever its QoS: its own compatibility check never answers "incompatible" (Zenoh
    delivers between any reliability/durability pair), and the type hash is not part of the
    lookup. We count the same way so a node sees the numbers an rmw_zenoh node sees.
    """
    return entity.kind == kind and entity.topic_name == topic and entity.type_name == type_name


def matched_count(
    entities: Iterable[Entity], topic: str, type_name: str | None, kind: EntityKind
) -> int:
    """How many `kind` endpoints are matched with ours (see :func:`matches`)."""
    return sum(1 for e in entities if matches(e, topic, type_name, kind))


OLD_RMW_ZENOH = (
    'its tokens show the durability default of rmw_zenoh 0.2.0-0.2.2, which reads only the '
    'old 77-byte attachment and aborts on the 33-byte one ros2lite and rmw_zenoh >= 0.2.4 '
    'send: upgrade rmw_zenoh_cpp on that host'
)


def old_rmw_zenoh_nodes(entities: Iterable[Entity]) -> list[str]:
    """Nodes whose tokens were written by rmw_zenoh 0.2.0-0.2.2 (sorted, one per node).

    Those releases (and 0.2.3) read only the old 77-byte keyed attachment and abort on
    today's 33-byte one. Their tokens give them away by the old durability default,
    TRANSIENT_LOCAL: they write `2` for a volatile endpoint (today's default, which current
    releases leave empty) and leave `/rosout`'s transient-local publisher empty (current
    releases write `1`). 0.2.3 already had today's default, so no token tells it apart.
    """
    found = set()
    for e in entities:
        if e.is_node or e.qos_chunk is None:
            continue
        durability = e.qos_chunk.split(':')[1] if e.qos_chunk.count(':') >= 2 else ''
        rosout = e.kind == EntityKind.PUBLISHER and e.topic_name == '/rosout'
        if durability == '2' or (rosout and durability == ''):
            found.add(e.node_fqn)
    return sorted(found)


# -- queries behind `topic list/info` and `node list/info` ---------------------------------------
# rcl_action has no entity kinds of its own: an action shows up as a node publishing (server) or
# subscribing (client) `<action>/_action/feedback`, typed `<pkg>/action/<Name>_FeedbackMessage`.

ACTION_FEEDBACK_SUFFIX = action_entity_name('', 'feedback')
ACTION_FEEDBACK_TYPE_SUFFIX = '_FeedbackMessage'


def topic_counts(entities: Iterable[Entity]) -> dict[str, tuple[int, int]]:
    """(publishers, subscriptions) per topic in one pass (`count()` per topic is quadratic)."""
    counts: dict[str, list[int]] = {}
    for e in entities:
        if e.kind in _TOPIC_KINDS and e.topic_name:
            pair = counts.setdefault(e.topic_name, [0, 0])
            pair[0 if e.kind == EntityKind.PUBLISHER else 1] += 1
    return {name: (p, s) for name, (p, s) in counts.items()}


def node_full_names(entities: Iterable[Entity], include_hidden: bool = False) -> list[str]:
    """Fully qualified name of every node instance, sorted; duplicates stay (one per instance).

    Like ros2cli, a node is hidden when its own name starts with '_' (the namespace is not
    looked at).
    """
    return sorted(
        node_fqn(ns, name)
        for name, ns in node_names_and_namespaces(entities)
        if include_hidden or not name.startswith('_')
    )


def _node_instances(
    entities: Iterable[Entity], node: str, namespace: str
) -> dict[tuple[str, int], list[Entity]]:
    ns = namespace or '/'
    out: dict[tuple[str, int], list[Entity]] = {}
    for e in entities:
        if e.node_name == node and e.namespace == ns:
            out.setdefault((e.zid, e.nid), []).append(e)
    return out


def _action_names(names_and_types: list[tuple[str, list[str]]]) -> list[tuple[str, list[str]]]:
    """Feedback topics → (action name, action types), following rcl_action's filter."""
    cut_name, cut_type = len(ACTION_FEEDBACK_SUFFIX), len(ACTION_FEEDBACK_TYPE_SUFFIX)
    return [
        (
            name[:-cut_name],
            [t[:-cut_type] if ACTION_FEEDBACK_TYPE_SUFFIX in t else t for t in types],
        )
        for name, types in names_and_types
        if ACTION_FEEDBACK_SUFFIX in name
    ]


def action_names_and_types(
    entities: Iterable[Entity], include_hidden: bool = False
) -> list[tuple[str, list[str]]]:
    """Every action in the graph (servers and clients alike), by name."""
    result = _action_names(_names_and_types(entities, _TOPIC_KINDS))
    return result if include_hidden else [r for r in result if not is_hidden_name(r[0])]


def action_endpoints(
    entities: Iterable[Entity], action_name: str
) -> tuple[list[tuple[str, list[str]]], list[tuple[str, list[str]]]]:
    """(clients, servers) of one action: (node full name, action types) per node instance.

    As rcl_action sees it, servers publish `<action>/_action/feedback` and clients subscribe
    to it; hidden nodes (the CLI's own) count too, as in `ros2 action info`.
    """
    from ros2lite.names import node_fqn

    feedback = action_name + ACTION_FEEDBACK_SUFFIX
    found: dict[EntityKind, dict[tuple[str, int], tuple[str, set[str]]]] = {
        EntityKind.SUBSCRIPTION: {},
        EntityKind.PUBLISHER: {},
    }
    for e in entities:
        if e.kind in found and e.topic_name == feedback and e.type_name:
            _, types = found[e.kind].setdefault(
                (e.zid, e.nid), (node_fqn(e.namespace, e.node_name), set())
            )
            types.add(
                e.type_name[: -len(ACTION_FEEDBACK_TYPE_SUFFIX)]
                if e.type_name.endswith(ACTION_FEEDBACK_TYPE_SUFFIX)
                else e.type_name
            )

    def listed(kind: EntityKind) -> list[tuple[str, list[str]]]:
        return sorted((name, sorted(types)) for name, types in found[kind].values())

    return listed(EntityKind.SUBSCRIPTION), listed(EntityKind.PUBLISHER)


@dataclass(frozen=True)
class NodeInfo:
    """What `ros2 node info` shows for one node instance; each list is (name, types) by name."""

    subscribers: list[tuple[str, list[str]]]
    publishers: list[tuple[str, list[str]]]
    service_servers: list[tuple[str, list[str]]]
    service_clients: list[tuple[str, list[str]]]
    action_servers: list[tuple[str, list[str]]]
    action_clients: list[tuple[str, list[str]]]


def node_info(
    entities: Iterable[Entity], node: str, namespace: str, include_hidden: bool = False
) -> NodeInfo | None:
    """The endpoints of one node instance, or None when no node has that name.

    With several instances sharing the name, one of them is described (the first by session
    and node id), as rmw_zenoh does. Hidden names are dropped unless `include_hidden`; action
    topics and services are hidden names (`_action`), so by default they only show up in the
    action sections, as in ros2cli.
    """
    instances = _node_instances(entities, node, namespace)
    if not instances:
        return None
    mine = instances[min(instances)]

    def of(kind: EntityKind) -> list[tuple[str, list[str]]]:
        return _names_and_types(mine, (kind,))

    def shown(items: list[tuple[str, list[str]]]) -> list[tuple[str, list[str]]]:
        return items if include_hidden else [i for i in items if not is_hidden_name(i[0])]

    pubs, subs = of(EntityKind.PUBLISHER), of(EntityKind.SUBSCRIPTION)
    return NodeInfo(
        subscribers=shown(subs),
        publishers=shown(pubs),
        service_servers=shown(of(EntityKind.SERVICE)),
        service_clients=shown(of(EntityKind.CLIENT)),
        action_servers=shown(_action_names(pubs)),
        action_clients=shown(_action_names(subs)),
    )


def format_endpoint_info(info: TopicEndpointInfo) -> str:
    """One endpoint as rclpy's `TopicEndpointInfo.__str__` prints it (no trailing newline)."""
    return str(info)


class GraphContext(Protocol):
    """What a node's graph queries ask of its context (:class:`ros2lite.context.Context` is
    one): named here, as the context makes the graph cache and so stands on this module."""

    @property
    def graph(self) -> GraphCache:
        """The context's live graph cache."""
        ...

    def ok(self) -> bool:
        """Whether the context is still initialized."""
        ...


class GraphMixin:
    """Node's graph queries, rclpy's `get_*`/`count_*`/`wait_for_node`, answered from the
    context's live `GraphCache`. Node supplies `context` and name resolution."""

    if TYPE_CHECKING:

        @property
        def context(self) -> GraphContext: ...

        def resolve_topic_name(self, topic: str, *, only_expand: bool = False) -> str: ...

        def resolve_service_name(self, service: str, *, only_expand: bool = False) -> str: ...

    def _entities(self) -> list[Entity]:
        entities: list[Entity] = self.context.graph.entities()
        return entities

    def get_node_names(self) -> list[str]:
        """Names of the nodes on the graph."""
        return [n for n, _ in self.get_node_names_and_namespaces()]

    def get_node_names_and_namespaces(self) -> list[tuple[str, str]]:
        """(name, namespace) of the nodes on the graph."""
        return node_names_and_namespaces(self._entities())

    def get_node_names_and_namespaces_with_enclaves(self) -> list[tuple[str, str, str]]:
        """(name, namespace, enclave) of every node in the graph."""
        seen: dict[tuple[str, int], tuple[str, str, str]] = {}
        for e in self._entities():
            seen.setdefault((e.zid, e.nid), (e.node_name, e.namespace, e.enclave))
        return sorted(seen.values(), key=lambda n: n[1].rstrip('/') + '/' + n[0])

    def get_fully_qualified_node_names(self) -> list[str]:
        """`/ns/name` of every node in the graph (this one included)."""
        return node_full_names(self._entities(), include_hidden=True)

    def wait_for_node(self, fully_qualified_node_name: str, timeout: float) -> bool:
        """Wait until a node of that name is in the graph; False if `timeout` s passed first
        (rclpy's; the name is made absolute if it is not)."""
        fqn = absolute_node_name(fully_qualified_node_name)
        context = self.context
        context.graph.wait_for(
            lambda entities: (
                fqn in node_full_names(entities, include_hidden=True) or not context.ok()
            ),
            timeout,
        )
        return fqn in self.get_fully_qualified_node_names()

    def get_topic_names_and_types(
        self, no_demangle: bool = False, *, include_hidden_topics: bool = True
    ) -> list[tuple[str, list[str]]]:
        """Every topic in the graph with its types, hidden ones too (as rcl lists them;
        tools filter those out). `no_demangle` is rclpy's DDS option: rmw_zenoh's names are
        never mangled."""
        return topic_names_and_types(self._entities(), include_hidden_topics)

    def get_service_names_and_types(self) -> list[tuple[str, list[str]]]:
        """(service, types) on the graph."""
        return service_names_and_types(self._entities(), include_hidden=True)

    def _by_node(self, node: str, namespace: str, kind: EntityKind) -> list[tuple[str, list[str]]]:
        return names_and_types_by_node(self._entities(), node, namespace, kind)

    def get_publisher_names_and_types_by_node(
        self, node_name: str, node_namespace: str
    ) -> list[tuple[str, list[str]]]:
        """(topic, types) that node publishes."""
        return self._by_node(node_name, node_namespace, EntityKind.PUBLISHER)

    def get_subscriber_names_and_types_by_node(
        self, node_name: str, node_namespace: str
    ) -> list[tuple[str, list[str]]]:
        """(topic, types) that node subscribes to."""
        return self._by_node(node_name, node_namespace, EntityKind.SUBSCRIPTION)

    def get_service_names_and_types_by_node(
        self, node_name: str, node_namespace: str
    ) -> list[tuple[str, list[str]]]:
        """(service, types) that node serves."""
        return self._by_node(node_name, node_namespace, EntityKind.SERVICE)

    def get_client_names_and_types_by_node(
        self, node_name: str, node_namespace: str
    ) -> list[tuple[str, list[str]]]:
        """(service, types) that node has clients of."""
        return self._by_node(node_name, node_namespace, EntityKind.CLIENT)

    def get_publishers_info_by_topic(self, topic_name: str) -> list[TopicEndpointInfo]:
        """Node, type, GID and QoS of each publisher of a topic."""
        return endpoints_by_topic(
            self._entities(), self.resolve_topic_name(topic_name), EntityKind.PUBLISHER
        )

    def get_subscriptions_info_by_topic(self, topic_name: str) -> list[TopicEndpointInfo]:
        """Node, type, GID and QoS of each subscription of a topic."""
        return endpoints_by_topic(
            self._entities(), self.resolve_topic_name(topic_name), EntityKind.SUBSCRIPTION
        )

    def count_publishers(self, topic_name: str) -> int:
        """How many publishers a topic has on the graph."""
        return len(self.get_publishers_info_by_topic(topic_name))

    def count_subscribers(self, topic_name: str) -> int:
        """How many subscriptions a topic has on the graph."""
        return len(self.get_subscriptions_info_by_topic(topic_name))

    def count_services(self, service_name: str) -> int:
        """How many servers a service has on the graph."""
        return count(self._entities(), self.resolve_service_name(service_name), EntityKind.SERVICE)

    def count_clients(self, service_name: str) -> int:
        """How many clients a service has on the graph."""
        return count(self._entities(), self.resolve_service_name(service_name), EntityKind.CLIENT)
