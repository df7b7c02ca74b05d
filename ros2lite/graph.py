"""The ROS graph as seen through rmw_zenoh liveliness tokens.

Two ways in: a live `GraphCache` that a node keeps up to date (like rmw_zenoh's graph cache), and
`snapshot()`, a one-shot liveliness query that returns once every token has answered — the CLI
uses it, so `topic list` needs no spin time and never misses a slow reply.
"""

from __future__ import annotations

import threading
from collections.abc import Callable, Iterable
from dataclasses import dataclass
from typing import Any

from ros2lite.transport.keys import Entity, EntityKind, is_hidden_name, parse_token
from ros2lite.transport.qos import QoSProfile

_TOPIC_KINDS = (EntityKind.PUBLISHER, EntityKind.SUBSCRIPTION)
_SERVICE_KINDS = (EntityKind.SERVICE, EntityKind.CLIENT)


@dataclass(frozen=True)
class TopicEndpointInfo:
    """What `ros2 topic info -v` prints for one endpoint (rclpy's TopicEndpointInfo)."""

    node_name: str
    node_namespace: str
    topic_type: str
    topic_type_hash: str
    endpoint_type: str          # 'PUBLISHER' or 'SUBSCRIPTION'
    endpoint_gid: bytes
    qos_profile: QoSProfile | None


def snapshot(session: Any, domain_id: int, timeout: float = 5.0) -> list[Entity]:
    """All entities in the domain, from one complete liveliness query."""
    import zenoh

    from ros2lite.transport.keys import liveliness_subscription_key
    # an explicit large channel: the default handler can stall past a few hundred replies
    replies = session.liveliness().get(liveliness_subscription_key(domain_id),
                                       zenoh.handlers.FifoChannel(1 << 16), timeout=timeout)
    out = []
    for reply in replies:
        sample = reply.ok
        if sample is not None:
            entity = parse_token(str(sample.key_expr))
            if entity is not None:
                out.append(entity)
    return out


class GraphCache:
    """Entities kept current from a liveliness subscriber with history."""

    def __init__(self, session: Any, domain_id: int) -> None:
        import zenoh

        from ros2lite.transport.keys import liveliness_subscription_key
        self._entities: dict[str, Entity] = {}
        self._cond = threading.Condition()
        self._listeners: list[Callable[[], None]] = []
        self._version = 0
        # seed synchronously (as rmw_zenoh does with a liveliness get) so the first query
        # after creation already sees the graph; the subscriber then keeps it current
        for entity in snapshot(session, domain_id):
            self._entities[entity.to_token()] = entity
        self._sub = session.liveliness().declare_subscriber(
            liveliness_subscription_key(domain_id), zenoh.handlers.Callback(self._on_sample),
            history=True)

    def _on_sample(self, sample: Any) -> None:
        import zenoh
        key = str(sample.key_expr)
        with self._cond:
            if sample.kind == zenoh.SampleKind.PUT:
                entity = parse_token(key)
                if entity is None:
                    return
                self._entities[key] = entity
            else:
                self._entities.pop(key, None)
            self._version += 1
            self._cond.notify_all()
            listeners = list(self._listeners)
        for listener in listeners:
            listener()

    def add_listener(self, fn: Callable[[], None]) -> None:
        with self._cond:
            self._listeners.append(fn)

    def remove_listener(self, fn: Callable[[], None]) -> None:
        with self._cond:
            if fn in self._listeners:
                self._listeners.remove(fn)

    def entities(self) -> list[Entity]:
        with self._cond:
            return list(self._entities.values())

    def wait_for(self, predicate: Callable[[list[Entity]], bool], timeout: float | None) -> bool:
        """Block until `predicate(entities)` holds or the timeout passes."""
        import time
        deadline = None if timeout is None else time.monotonic() + timeout
        with self._cond:
            while not predicate(list(self._entities.values())):
                remaining = None if deadline is None else deadline - time.monotonic()
                if remaining is not None and remaining <= 0:
                    return False
                self._cond.wait(remaining if remaining is not None else 1.0)
        return True

    def close(self) -> None:
        from ros2lite.context import undeclare_quietly
        undeclare_quietly(self._sub)


# -- queries over a list of entities (shared by GraphCache and snapshot users) -------------------

def node_names_and_namespaces(entities: Iterable[Entity]) -> list[tuple[str, str]]:
    """(name, namespace) of every node, once per node instance, in name order."""
    seen: dict[tuple[str, int], tuple[str, str]] = {}
    for e in entities:
        seen.setdefault((e.zid, e.nid), (e.node_name, e.namespace))
    return sorted(seen.values(), key=lambda nn: (nn[1].rstrip('/') + '/' + nn[0]))


def _names_and_types(entities: Iterable[Entity], kinds: tuple[EntityKind, ...]
                     ) -> list[tuple[str, list[str]]]:
    table: dict[str, set[str]] = {}
    for e in entities:
        if e.kind in kinds and e.topic_name and e.type_name:
            table.setdefault(e.topic_name, set()).add(e.type_name)
    return [(name, sorted(types)) for name, types in sorted(table.items())]


def topic_names_and_types(entities: Iterable[Entity], include_hidden: bool = False
                          ) -> list[tuple[str, list[str]]]:
    result = _names_and_types(entities, _TOPIC_KINDS)
    return result if include_hidden else [r for r in result if not is_hidden_name(r[0])]


def service_names_and_types(entities: Iterable[Entity], include_hidden: bool = False
                            ) -> list[tuple[str, list[str]]]:
    result = _names_and_types(entities, _SERVICE_KINDS)
    return result if include_hidden else [r for r in result if not is_hidden_name(r[0])]


def _of_node(entities: Iterable[Entity], node: str, namespace: str) -> list[Entity]:
    ns = namespace or '/'
    return [e for e in entities if e.node_name == node and e.namespace == ns]


def names_and_types_by_node(entities: Iterable[Entity], node: str, namespace: str,
                            kind: EntityKind) -> list[tuple[str, list[str]]]:
    return _names_and_types(_of_node(entities, node, namespace), (kind,))


def endpoints_by_topic(entities: Iterable[Entity], topic: str, kind: EntityKind
                       ) -> list[TopicEndpointInfo]:
    from ros2lite.transport.attachment import gid_from_token
    label = 'PUBLISHER' if kind == EntityKind.PUBLISHER else 'SUBSCRIPTION'
    return [
        TopicEndpointInfo(e.node_name, e.namespace, e.type_name or '', e.type_hash or '',
                          label, gid_from_token(e.to_token()), e.qos)
        for e in entities if e.kind == kind and e.topic_name == topic
    ]


def count(entities: Iterable[Entity], topic: str, kind: EntityKind) -> int:
    return sum(1 for e in entities if e.kind == kind and e.topic_name == topic)
