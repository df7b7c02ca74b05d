"""The node/topic graph rqt_graph draws, built from who publishes and subscribes what.

Nodes are ellipses, topics boxes, and arrows run publisher -> topic -> subscriber. As in
rqt_graph's default view, hidden nodes and topics (a name part starting with '_') are left
out, and so are debug topics (/rosout, /parameter_events) and leaf topics (those with
publishers but no subscribers, or the reverse) unless asked for.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field

from ros2lite.graph import Entity, EntityKind
from ros2lite.names import is_hidden_name

DEBUG_TOPICS = frozenset({'/rosout', '/parameter_events'})


@dataclass(frozen=True)
class Endpoint:
    """One node publishing ('pub') or subscribing ('sub') one topic."""

    node: str  # fully qualified
    kind: str
    topic: str


@dataclass(frozen=True)
class Options:
    """Which nodes and topics the picture leaves out (rqt_graph's check boxes)."""

    include_hidden: bool = False
    show_debug: bool = False
    show_leaf_topics: bool = False


@dataclass(frozen=True)
class Graph:
    """What to draw: node and topic names, and edges (source, target) between them.

    Other pictures laid out the same way (rqt_tf_tree's frames) add `notes`, vertices drawn as
    bare text (an edge's label, placed on the edge as Graphviz places its labels), `labels`
    where the text shown differs from a vertex's name (several lines too), and may run
    `top_down` instead of left to right."""

    nodes: tuple[str, ...]
    topics: tuple[str, ...]
    edges: tuple[tuple[str, str], ...] = field(default=())
    notes: tuple[str, ...] = ()
    labels: tuple[tuple[str, str], ...] = ()  # (name, text shown)
    top_down: bool = False

    def text(self, name: str) -> str:
        """What the vertex `name` shows."""
        index = self.__dict__.get('_label_index')
        if index is None:  # built once: a lookup per vertex stays constant (2,000 frames)
            index = dict(self.labels)
            object.__setattr__(self, '_label_index', index)
        return str(index.get(name, name))


def build(nodes: Iterable[str], endpoints: Iterable[Endpoint], options: Options) -> Graph:
    """The graph of `nodes` (fully qualified names) and their `endpoints`, filtered."""
    shown_nodes = sorted({n for n in nodes if options.include_hidden or not is_hidden_name(n)})
    keep = set(shown_nodes)
    pubs: dict[str, set[str]] = {}
    subs: dict[str, set[str]] = {}
    for e in endpoints:
        if e.node not in keep:
            continue
        if not options.include_hidden and is_hidden_name(e.topic):
            continue
        if not options.show_debug and e.topic in DEBUG_TOPICS:
            continue
        (pubs if e.kind == 'pub' else subs).setdefault(e.topic, set()).add(e.node)
    topics = sorted(
        t
        for t in set(pubs) | set(subs)
        if options.show_leaf_topics or (pubs.get(t) and subs.get(t))
    )
    edges = []
    for t in topics:
        edges += [(n, t) for n in sorted(pubs.get(t, ()))]
        edges += [(t, n) for n in sorted(subs.get(t, ()))]
    return Graph(tuple(shown_nodes), tuple(topics), tuple(edges))


def from_entities(entities: Iterable[Entity], options: Options) -> Graph:
    """The graph a set of graph entities (a complete liveliness query) describes."""
    entities = list(entities)
    names = sorted({e.node_fqn for e in entities if e.is_node})
    kinds = {EntityKind.PUBLISHER: 'pub', EntityKind.SUBSCRIPTION: 'sub'}
    endpoints = [
        Endpoint(e.node_fqn, kinds[e.kind], e.topic_name)
        for e in entities
        if e.kind in kinds and e.topic_name
    ]
    return build(names, endpoints, options)
