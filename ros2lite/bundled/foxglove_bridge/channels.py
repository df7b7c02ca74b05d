"""Following the graph: every visible topic a channel, subscribed in Zenoh only while a
client watches it; the connection graph sent to the clients that asked for it."""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import foxglove

from ros2lite.bundled.foxglove_bridge.state import BridgeState, matches
from ros2lite.graph import EntityKind
from ros2lite.names import is_hidden_name
from ros2lite.qos import HistoryPolicy, QoSProfile, match_publishers_qos

if TYPE_CHECKING:
    from ros2lite.graph import Entity
    from ros2lite.monitor.subscription import MonitoredSubscription


@dataclass
class _Topic:
    """One advertised (topic, type): its channel and, while clients watch, its subscription."""

    name: str
    type_name: str
    channel: foxglove.Channel
    subscribers: set[int] = field(default_factory=set)  # client ids
    subscription: MonitoredSubscription | None = None


class GraphChannels:
    """Topics -> channels, and the connection graph."""

    def __init__(self, state: BridgeState, topic_patterns: list[re.Pattern[str]]) -> None:
        self.state = state
        self.topic_patterns = topic_patterns
        self.topics: dict[tuple[str, str], _Topic] = {}
        self.by_channel: dict[int, _Topic] = {}
        self.graph_subscribed = False
        self.last_graph: object = None

    def refresh(self, entities: list[Entity]) -> None:
        """Bring channels in line with the graph's topics; send the connection graph."""
        from ros2lite.interfaces import definition_text
        from ros2lite.remote_types import ensure_type

        state = self.state
        wanted: dict[tuple[str, str], list[Entity]] = {}
        for e in entities:
            if not (e.topic_name and e.type_name):
                continue
            if e.kind in (EntityKind.PUBLISHER, EntityKind.SUBSCRIPTION) and visible(
                state, e.topic_name, self.topic_patterns
            ):
                wanted.setdefault((e.topic_name, e.type_name), []).append(e)
        for key in list(self.topics):
            if key not in wanted:
                topic = self.topics.pop(key)
                self.by_channel.pop(topic.channel.id(), None)
                self._unsubscribe_topic(topic)
                topic.channel.close()
        for (name, type_name), _ in sorted(wanted.items()):
            if (name, type_name) in self.topics or type_name in state.unknown_types:
                continue
            try:
                ensure_type(lambda: state.node, entities, type_name, name)
                text = definition_text(type_name)
            except Exception as e:  # a type not defined here: no schema a client could use
                state.unknown_types.add(type_name)
                state.warn(f"Topic '{name}': type {type_name} is unknown here ({e}); not shown")
                continue
            schema = foxglove.Schema(name=type_name, encoding='ros2msg', data=text.encode())
            channel = foxglove.Channel(
                name, message_encoding='cdr', schema=schema, context=state.context
            )
            topic = _Topic(name, type_name, channel)
            self.topics[(name, type_name)] = topic
            self.by_channel[channel.id()] = topic
        for (name, type_name), topic in self.topics.items():
            if topic.subscription is not None:
                continue
            if topic.subscribers:  # publishers came back for a channel clients still watch
                self._subscribe_topic(topic, wanted.get((name, type_name), []))
        if self.graph_subscribed:
            self._publish_graph(entities)

    def close(self) -> None:
        """Every subscription undeclared, every channel closed."""
        for topic in list(self.topics.values()):
            self._unsubscribe_topic(topic)
            topic.channel.close()
        self.topics.clear()
        self.by_channel.clear()

    def subscribe(self, client_id: int, channel_id: int) -> None:
        topic = self.by_channel.get(channel_id)
        if topic is None:
            return
        topic.subscribers.add(client_id)
        if topic.subscription is None:
            pubs = [
                e
                for e in self.state.node.context.graph.entities()
                if e.kind is EntityKind.PUBLISHER
                and e.topic_name == topic.name
                and e.type_name == topic.type_name
            ]
            self._subscribe_topic(topic, pubs)

    def _subscribe_topic(self, topic: _Topic, pubs: list[Entity]) -> None:
        from ros2lite.bag.definitions import type_ref
        from ros2lite.monitor.subscription import MonitoredSubscription

        s = self.state.settings
        depth = sum(p.qos.depth for p in pubs if p.qos is not None)
        depth = min(max(depth, s.min_qos_depth, 1), max(s.max_qos_depth, 1))
        offered = [p.qos for p in pubs if p.qos is not None and p.kind is EntityKind.PUBLISHER]
        qos = match_publishers_qos(
            QoSProfile(history=HistoryPolicy.KEEP_LAST, depth=depth), offered
        ).profile
        hashes = {p.type_hash for p in pubs if p.type_hash}
        msg_type: type | str = topic.type_name
        if len(hashes) == 1:
            # the publishers' own hash, so a type that changed here still matches them
            msg_type = type_ref(topic.type_name, next(iter(hashes)))
        log = topic.channel.base.log
        clock = self.state.node.get_clock()

        def receive(data: bytes, _attachment: bytes, received: int) -> None:
            if clock.ros_time_is_active:
                received = clock.now().nanoseconds
            log(data, received)

        topic.subscription = MonitoredSubscription(
            self.state.node, msg_type, topic.name, None, qos, on_payload=receive
        )

    def unsubscribe(self, client_id: int, channel_id: int) -> None:
        topic = self.by_channel.get(channel_id)
        if topic is None:
            return
        topic.subscribers.discard(client_id)
        if not topic.subscribers:
            self._unsubscribe_topic(topic)

    def _unsubscribe_topic(self, topic: _Topic) -> None:
        sub, topic.subscription = topic.subscription, None
        if sub is not None:
            self.state.node.destroy_subscription(sub)

    # -- connection graph ----------------------------------------------------------------------
    def _publish_graph(self, entities: list[Entity]) -> None:
        server = self.state.server
        assert server is not None
        published: dict[str, set[str]] = {}
        subscribed: dict[str, set[str]] = {}
        provided: dict[str, set[str]] = {}
        table = {
            EntityKind.PUBLISHER: published,
            EntityKind.SUBSCRIPTION: subscribed,
            EntityKind.SERVICE: provided,
        }
        for e in entities:
            into = table.get(e.kind)
            if into is not None and e.topic_name:
                into.setdefault(e.topic_name, set()).add(e.node_fqn)
        picture = tuple(
            tuple(sorted((k, tuple(sorted(v))) for k, v in t.items()))
            for t in (published, subscribed, provided)
        )
        if picture == self.last_graph:
            return
        self.last_graph = picture
        graph = foxglove.ConnectionGraph()
        for topic, ids in published.items():
            graph.set_published_topic(topic, sorted(ids))
        for topic, ids in subscribed.items():
            graph.set_subscribed_topic(topic, sorted(ids))
        for service, ids in provided.items():
            graph.set_advertised_service(service, sorted(ids))
        server.publish_connection_graph(graph)


def visible(state: BridgeState, name: str, patterns: list[re.Pattern[str]]) -> bool:
    """Whether a topic or service is shown: whitelisted, and not hidden unless asked."""
    return (state.settings.include_hidden or not is_hidden_name(name)) and matches(patterns, name)
