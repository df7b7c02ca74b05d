"""Matched counts and events follow rmw_zenoh's graph cache, not DDS's request/offer rules.

rmw_zenoh files each endpoint by topic name, type name and QoS string; a publisher's matched
subscriptions are every subscription under the same name and type whose QoS its own
compatibility check does not call an error, and that check never does (Zenoh delivers between
any reliability/durability pair; transient-local to volatile is only a warning). So every QoS
pair below is matched, a different type name is not, and no incompatible-QoS event fires.
"""

from __future__ import annotations

from typing import Any

from ros2lite.context import Context
from ros2lite.duration import Duration
from ros2lite.event_handler import PublisherEventCallbacks, SubscriptionEventCallbacks
from ros2lite.executors import SingleThreadedExecutor
from ros2lite.graph import matched_count, matches
from ros2lite.node import Node
from ros2lite.qos import DurabilityPolicy as D
from ros2lite.qos import LivelinessPolicy as L
from ros2lite.qos import QoSProfile
from ros2lite.qos import ReliabilityPolicy as R
from ros2lite.transport.keys import EntityKind, endpoint_token, parse_token
from tests.spinning import spin_until

STRING = 'std_msgs/msg/String'
HASH = 'RIHS01_df668c740482bbd48fb39d76a70dfd4bd59db1288021743503259e948f6b1a18'


def _q(**kw: Any) -> QoSProfile:
    return QoSProfile(depth=kw.pop('depth', 10), **kw)


# (publisher QoS, subscription QoS): each is a pair DDS calls incompatible (or a plain one),
# and each is matched on rmw_zenoh.
PAIRS = [
    ('plain', _q(), _q()),
    ('best effort pub, reliable sub', _q(reliability=R.BEST_EFFORT), _q(reliability=R.RELIABLE)),
    ('reliable pub, best effort sub', _q(), _q(reliability=R.BEST_EFFORT)),
    ('volatile pub, transient sub', _q(), _q(durability=D.TRANSIENT_LOCAL)),
    ('transient pub, volatile sub', _q(durability=D.TRANSIENT_LOCAL), _q()),
    (
        'best effort volatile pub, reliable transient sub',
        _q(reliability=R.BEST_EFFORT),
        _q(durability=D.TRANSIENT_LOCAL),
    ),
    ('sub deadline, pub none', _q(), _q(deadline=Duration(seconds=1))),
    (
        'sub deadline shorter',
        _q(deadline=Duration(seconds=2)),
        _q(deadline=Duration(seconds=1)),
    ),
    ('automatic pub, manual sub', _q(), _q(liveliness=L.MANUAL_BY_TOPIC)),
    (
        'sub lease shorter',
        _q(liveliness_lease_duration=Duration(seconds=2)),
        _q(liveliness_lease_duration=Duration(seconds=1)),
    ),
    ('depths differ', _q(depth=1), _q(depth=1000)),
]


def _token(kind: EntityKind, topic: str, type_name: str, qos: QoSProfile, eid: int) -> Any:
    key = endpoint_token(0, 'aa' * 16, 1, eid, kind, '/', 'n', topic, type_name, HASH, qos)
    entity = parse_token(key, strict=True)
    assert entity is not None
    return entity


def test_rule_table_by_hand_made_tokens() -> None:
    """The rule itself: name and type decide, QoS and hash do not (rmw_zenoh's lookup has
    no hash in it)."""
    for label, pub_qos, sub_qos in PAIRS:
        sub = _token(EntityKind.SUBSCRIPTION, '/t', STRING, sub_qos, 2)
        assert matches(sub, '/t', STRING, EntityKind.SUBSCRIPTION), label
        pub = _token(EntityKind.PUBLISHER, '/t', STRING, pub_qos, 3)
        assert matches(pub, '/t', STRING, EntityKind.PUBLISHER), label
    other_type = _token(EntityKind.SUBSCRIPTION, '/t', 'std_msgs/msg/Int32', _q(), 4)
    other_topic = _token(EntityKind.SUBSCRIPTION, '/u', STRING, _q(), 5)
    publisher = _token(EntityKind.PUBLISHER, '/t', STRING, _q(), 6)
    entities = [other_type, other_topic, publisher]
    assert matched_count(entities, '/t', STRING, EntityKind.SUBSCRIPTION) == 0
    rehashed = parse_token(
        endpoint_token(
            0,
            'bb' * 16,
            1,
            7,
            EntityKind.SUBSCRIPTION,
            '/',
            'n',
            '/t',
            STRING,
            'RIHS01_' + '0' * 64,
            _q(),
        ),
        strict=True,
    )
    assert rehashed is not None and matches(rehashed, '/t', STRING, EntityKind.SUBSCRIPTION)


def test_counts_and_matched_events_on_a_live_graph(ros_context: Any, ros_router: str) -> None:
    """Every pair of the table, over two contexts: both counts 1, a matched event on each
    side with current_count 1, and no incompatible-QoS event anywhere."""
    node = Node('offers', context=ros_context)
    matched: dict[str, list[Any]] = {}
    incompatible: list[Any] = []
    pubs = []
    for i, (_label, pub_qos, _) in enumerate(PAIRS):
        events = matched.setdefault(f'p{i}', [])
        pubs.append(
            node.create_publisher(
                STRING,
                f'pair{i}',
                pub_qos,
                event_callbacks=PublisherEventCallbacks(
                    matched=events.append, incompatible_qos=incompatible.append
                ),
            )
        )
    executor = SingleThreadedExecutor(context=ros_context)
    executor.add_node(node)
    other = Context().init([])
    try:
        peer = Node('requests', context=other)
        subs = []
        for i, (_label, _, sub_qos) in enumerate(PAIRS):
            events = matched.setdefault(f's{i}', [])
            subs.append(
                peer.create_subscription(
                    STRING,
                    f'pair{i}',
                    lambda m: None,
                    sub_qos,
                    event_callbacks=SubscriptionEventCallbacks(
                        matched=events.append, incompatible_qos=incompatible.append
                    ),
                )
            )
        # a subscription of another type on a topic of the table is not matched
        peer.create_subscription('std_msgs/msg/Int32', 'pair0', lambda m: None, 10)
        peer_executor = SingleThreadedExecutor(context=other)
        peer_executor.add_node(peer)

        def all_matched() -> bool:
            peer_executor.spin_once(timeout_sec=0)
            # the Int32 one's token may come after every String pair has matched
            return (
                all(matched[f'p{i}'] and matched[f's{i}'] for i in range(len(PAIRS)))
                and node.count_subscribers('pair0') == 2
            )

        spin_until(executor, all_matched, timeout=15)
        for i, (label, _, _) in enumerate(PAIRS):
            assert pubs[i].get_subscription_count() == 1, label
            assert subs[i].get_publisher_count() == 1, label
            assert matched[f'p{i}'][-1].current_count == 1, label
            assert matched[f's{i}'][-1].current_count == 1, label
        assert incompatible == []
        assert node.count_subscribers('pair0') == 2  # rcl's count is by name alone
    finally:
        other.shutdown()
