"""Watching one topic from outside, as `topic echo/hz/bw/delay` and scripts do it.

A :class:`TopicMonitor` resolves the topic name, finds its type in the graph (waiting until
some endpoint announces it, if asked), chooses a subscription QoS that connects to every
publisher, and subscribes in the way the consumer needs: arrival times only (rates,
bandwidth, lost messages: nothing decoded, nothing queued), raw samples on the executor, or
payloads on arrival (a recorder). Statistics come from :mod:`ros2lite.monitor.stats`.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass

from ros2lite.exceptions import Ros2liteError
from ros2lite.graph import Entity, EntityKind, endpoints_by_topic
from ros2lite.monitor.subscription import MonitoredSubscription, topic_types
from ros2lite.node import Node
from ros2lite.qos import MatchedQoS, QoSProfile, match_publishers_qos
from ros2lite.subscription import MessageInfo, Subscription

__all__ = ['MultipleTypesError', 'TopicMonitor', 'TypeMismatch', 'type_mismatch']

EntitiesFn = Callable[[], list[Entity]]


class MultipleTypesError(Ros2liteError):
    """Endpoints of the topic use more than one type, so there is no one type to watch."""

    def __init__(self, topic: str, types: list[str]) -> None:
        self.topic = topic
        self.types = types
        super().__init__(f"topic '{topic}' has more than one type: [{', '.join(types)}]")


@dataclass(frozen=True)
class TypeMismatch:
    """Why a subscription of `type_name` would hear none of the topic's publishers."""

    type_name: str
    type_hash: str
    published_types: list[str]  # what the publishers use instead
    published_hashes: list[str]  # their hashes, when they use our type's name

    @property
    def same_name(self) -> bool:
        """The publishers use this type's name with another definition (hash)."""
        return self.type_name in self.published_types


def type_mismatch(entities: list[Entity], topic: str, type_name: str) -> TypeMismatch | None:
    """A mismatch when the topic has publishers and none uses `type_name` with our hash: the
    data key holds both, so such a subscription would wait forever in silence."""
    from ros2lite.interfaces import type_hash

    pubs = endpoints_by_topic(entities, topic, EntityKind.PUBLISHER)
    ours = type_hash(type_name)
    if not pubs or any(p.topic_type == type_name and p.topic_type_hash == ours for p in pubs):
        return None
    names = sorted({p.topic_type for p in pubs})
    hashes = sorted({p.topic_type_hash for p in pubs if p.topic_type == type_name})
    return TypeMismatch(type_name, ours, names, hashes)


class TopicMonitor:
    """One topic watched from `node` (normally a tool's hidden node): see the module doc.

    `entities()` answers graph questions (a tool's snapshot query, or a node's cache).
    """

    def __init__(self, node: Node, topic: str, entities: EntitiesFn) -> None:
        self.node = node
        self.name = topic  # as the user wrote it
        self.topic = node.resolve_topic_name(topic)
        self._entities = entities

    # -- what the graph says ---------------------------------------------------------------
    def graph_type(self) -> str | None:
        """The one type the graph knows for the topic (None if no endpoint uses it yet)."""
        types = topic_types(self._entities(), self.topic)
        if len(types) > 1:
            raise MultipleTypesError(self.topic, types)
        return types[0] if types else None

    def wait_for_type(
        self, on_waiting: Callable[[], object] | None = None, poll: float = 0.1
    ) -> str:
        """The topic's type, waiting until some endpoint announces it; `on_waiting()` is
        called once if it has to wait."""
        found = self.graph_type()
        if found is None and on_waiting is not None:
            on_waiting()
        while found is None:
            time.sleep(poll)
            found = self.graph_type()
        return found

    def matched_qos(self, profile: QoSProfile) -> MatchedQoS:
        """`profile`, with reliability and durability lowered to what every publisher
        offers (rmw's BEST_AVAILABLE rule)."""
        pubs = endpoints_by_topic(self._entities(), self.topic, EntityKind.PUBLISHER)
        return match_publishers_qos(profile, [p.qos_profile for p in pubs])

    def publisher_gids(self) -> set[bytes]:
        """The GIDs of the topic's publishers in the graph now."""
        pubs = endpoints_by_topic(self._entities(), self.topic, EntityKind.PUBLISHER)
        return {bytes(p.endpoint_gid) for p in pubs}

    def type_mismatch(self, type_name: str) -> TypeMismatch | None:
        """See :func:`type_mismatch`."""
        return type_mismatch(self._entities(), self.topic, type_name)

    # -- subscribing ---------------------------------------------------------------------------
    def on_arrival(
        self,
        type_name: str,
        qos: QoSProfile,
        hook: Callable[[int, bytes, int], object],
        callback: Callable[[bytes, MessageInfo], object] | None = None,
    ) -> Subscription:
        """`hook(size, attachment, arrival_ns)` on the receive thread for every sample (what
        rates, bandwidth and lost-message counts need); `callback(cdr, info)` also gets the
        samples on the executor when given."""
        return MonitoredSubscription(
            self.node, type_name, self.topic, callback, qos, on_arrival=hook
        )

    def on_sample(
        self, type_name: str, qos: QoSProfile, callback: Callable[[bytes, MessageInfo], object]
    ) -> Subscription:
        """`callback(cdr, info)` on the executor for each sample, undecoded."""
        return self.node.create_subscription(type_name, self.topic, callback, qos, raw=True)
