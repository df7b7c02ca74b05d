"""QoS events from the live graph: matched counts (any QoS, as rmw_zenoh counts them) and an
incompatible type, across nodes of two processes' worth of contexts."""

from __future__ import annotations

from typing import Any

import pytest

from ros2lite.context import Context
from ros2lite.event_handler import (
    PublisherEventCallbacks,
    QoSPublisherMatchedInfo,
    SubscriptionEventCallbacks,
    UnsupportedEventTypeError,
)
from ros2lite.executors import SingleThreadedExecutor
from ros2lite.node import Node
from ros2lite.qos import DurabilityPolicy, QoSProfile
from tests.spinning import spin_until


def test_matched_and_incompatible_events(ros_context: Any, ros_router: str) -> None:
    node = Node('evented', context=ros_context)
    matched: list[Any] = []
    incompatible: list[Any] = []
    types: list[Any] = []
    pub = node.create_publisher(
        'std_msgs/msg/String',
        'events',
        10,
        event_callbacks=PublisherEventCallbacks(
            matched=matched.append, incompatible_qos=incompatible.append
        ),
    )
    assert len(pub.event_handlers) == 3  # and the default incompatible-type warning
    node.create_subscription(
        'std_msgs/msg/Int32',
        'events',
        lambda m: None,
        10,
        event_callbacks=SubscriptionEventCallbacks(incompatible_type=types.append),
    )
    executor = SingleThreadedExecutor(context=ros_context)
    executor.add_node(node)
    other = Context().init([])  # another participant, seen through the graph
    try:
        peer = Node('peer', context=other)
        sub = peer.create_subscription('std_msgs/msg/String', 'events', lambda m: None, 10)
        spin_until(executor, lambda: matched and types, timeout=10)
        assert matched[0] == QoSPublisherMatchedInfo(1, 1, 1, 1)
        assert types[0].total_count >= 1
        peer.create_subscription(
            'std_msgs/msg/String',
            'events',
            lambda m: None,
            QoSProfile(depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL),
        )
        # DDS would call this pair incompatible; rmw_zenoh matches it and raises nothing
        spin_until(executor, lambda: matched[-1].current_count == 2, timeout=10)
        assert incompatible == []
        peer.destroy_subscription(sub)
        spin_until(executor, lambda: matched[-1].current_count == 1, timeout=10)
        assert matched[-1].current_count_change == -1
    finally:
        other.shutdown()


def test_events_rmw_zenoh_does_not_have(ros_context: Any) -> None:
    node = Node('undeadlined', context=ros_context)
    with pytest.raises(UnsupportedEventTypeError, match='DEADLINE'):
        node.create_publisher(
            'std_msgs/msg/String',
            'd',
            10,
            event_callbacks=PublisherEventCallbacks(deadline=lambda info: None),
        )
