"""The graph queries behind `topic list/info` and `node list/info`, on parsed tokens."""

from __future__ import annotations

from ros2lite.graph import (
    TopicEndpointInfo,
    action_names_and_types,
    format_endpoint_info,
    format_gid,
    node_full_names,
    node_info,
    topic_counts,
)
from ros2lite.qos import HistoryPolicy, QoSProfile
from ros2lite.transport.keys import Entity, EntityKind, endpoint_token, node_token, parse_token

ZID_A = 'aac3178e146ba6f1fc6e6a4085e77f21'
ZID_B = '8b20917502ee955ac4476e0266340d5c'
HASH = 'RIHS01_' + '1' * 64


def nn(zid: str, nid: int, ns: str, name: str) -> Entity:
    entity = parse_token(node_token(0, zid, nid, ns, name))
    assert entity is not None
    return entity


def ep(
    zid: str,
    nid: int,
    eid: int,
    kind: EntityKind,
    ns: str,
    name: str,
    topic: str,
    type_name: str = 'std_msgs/msg/String',
) -> Entity:
    entity = parse_token(
        endpoint_token(
            0, zid, nid, eid, kind, ns, name, topic, type_name, HASH, QoSProfile(depth=10)
        )
    )
    assert entity is not None
    return entity


def test_topic_counts_per_direction() -> None:
    P, S = EntityKind.PUBLISHER, EntityKind.SUBSCRIPTION
    entities = [
        ep(ZID_A, 0, 1, P, '/', 'a', '/t'),
        ep(ZID_A, 0, 2, S, '/', 'a', '/t'),
        ep(ZID_B, 0, 1, S, '/', 'b', '/t'),
        ep(ZID_B, 0, 2, P, '/', 'b', '/u'),
        ep(ZID_B, 0, 3, EntityKind.SERVICE, '/', 'b', '/srv', 'std_srvs/srv/Empty'),
        nn(ZID_B, 0, '/', 'b'),
    ]
    assert topic_counts(entities) == {'/t': (1, 2), '/u': (1, 0)}


def test_node_full_names_keep_instances_and_hide_by_own_name() -> None:
    entities = [
        nn(ZID_A, 0, '/', 'talker'),
        nn(ZID_B, 0, '/', 'talker'),
        nn(ZID_B, 3, '/x', '_hidden'),
        nn(ZID_B, 4, '/_ns', 'shown'),
        # an endpoint without its NN token still makes a node
        ep(ZID_A, 7, 8, EntityKind.PUBLISHER, '/r', 'ghost', '/t'),
    ]
    assert node_full_names(entities) == ['/_ns/shown', '/r/ghost', '/talker', '/talker']
    assert node_full_names(entities, include_hidden=True) == [
        '/_ns/shown',
        '/r/ghost',
        '/talker',
        '/talker',
        '/x/_hidden',
    ]


def test_action_names_follow_rcl_action() -> None:
    P, S = EntityKind.PUBLISHER, EntityKind.SUBSCRIPTION
    fb = 'example_interfaces/action/Fibonacci_FeedbackMessage'
    entities = [
        ep(ZID_A, 0, 1, P, '/', 's', '/fib/_action/feedback', fb),
        ep(ZID_A, 0, 2, P, '/', 's', '/fib/_action/status', 'action_msgs/msg/GoalStatusArray'),
        ep(ZID_B, 0, 1, S, '/', 'c', '/ns/go/_action/feedback', fb),
        ep(ZID_B, 0, 2, P, '/', 'c', '/not_an_action', fb),
    ]
    assert action_names_and_types(entities) == [
        ('/fib', ['example_interfaces/action/Fibonacci']),
        ('/ns/go', ['example_interfaces/action/Fibonacci']),
    ]


def test_node_info_describes_one_instance() -> None:
    P = EntityKind.PUBLISHER
    entities = [
        nn(ZID_A, 0, '/', 'twin'),
        ep(ZID_A, 0, 1, P, '/', 'twin', '/from_a'),
        nn(ZID_B, 5, '/', 'twin'),
        ep(ZID_B, 5, 6, P, '/', 'twin', '/from_b'),
        ep(ZID_B, 5, 7, P, '/', 'twin', '/_hidden'),
    ]
    info = node_info(entities, 'twin', '/')
    assert info is not None
    # the first instance by (session id, node id): ZID_B sorts before ZID_A
    assert info.publishers == [('/from_b', ['std_msgs/msg/String'])]
    shown = node_info(entities, 'twin', '/', include_hidden=True)
    assert shown is not None and [n for n, _ in shown.publishers] == ['/_hidden', '/from_b']
    assert node_info(entities, 'nobody', '/') is None
    assert node_info(entities, 'twin', '/other') is None


def test_format_endpoint_info_without_a_decodable_qos() -> None:
    info = TopicEndpointInfo('n', '/', 'a/msg/B', HASH, 'SUBSCRIPTION', bytes(range(16)), None)
    assert format_endpoint_info(info).splitlines()[5:] == [
        'GID: 00.01.02.03.04.05.06.07.08.09.0a.0b.0c.0d.0e.0f',
        'QoS profile:',
        '  Reliability: UNKNOWN',
        '  History (Depth): UNKNOWN',
        '  Durability: UNKNOWN',
        '  Lifespan: 0 nanoseconds',
        '  Deadline: 0 nanoseconds',
        '  Liveliness: UNKNOWN',
        '  Liveliness lease duration: 0 nanoseconds',
    ]


def test_history_depth_only_for_keep_last() -> None:
    base = TopicEndpointInfo('n', '/', 'a/msg/B', HASH, 'PUBLISHER', bytes(16), QoSProfile(depth=3))
    assert '  History (Depth): KEEP_LAST (3)' in format_endpoint_info(base)
    keep_all = TopicEndpointInfo(
        'n',
        '/',
        'a/msg/B',
        HASH,
        'PUBLISHER',
        bytes(16),
        QoSProfile(history=HistoryPolicy.KEEP_ALL, depth=3),
    )
    assert '  History (Depth): KEEP_ALL\n' in format_endpoint_info(keep_all)
    assert format_gid(b'\xff\x00') == 'ff.00'
