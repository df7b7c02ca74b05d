"""`topic info [-v]`: type, counts and rclpy-style endpoint blocks, byte for byte."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import pytest

from ros2lite.qos import (
    DurabilityPolicy,
    Duration,
    HistoryPolicy,
    LivelinessPolicy,
    QoSProfile,
    ReliabilityPolicy,
)
from ros2lite.transport.attachment import gid_from_token

from ..graph_helpers import (
    STRING,
    STRING_HASH,
    TokenGraph,
    dotted,
    private_domain,
    settle,
    start_node,
)

Run = Callable[..., Any]


def dots(key: str) -> str:
    return dotted(gid_from_token(key).hex())


@pytest.fixture
def graph(ros_router: str, monkeypatch: pytest.MonkeyPatch) -> Any:
    with TokenGraph(private_domain(monkeypatch)) as g:
        yield g


def test_counts(run: Run, graph: TokenGraph) -> None:
    graph.node('talker').pub('/chatter', type_hash=STRING_HASH)
    graph.node('a').sub('/chatter')
    graph.node('b', '/ns').sub('/chatter')
    expected = 'Type: std_msgs/msg/String\nPublisher count: 1\nSubscription count: 2\n'
    result = settle(run, 'topic', 'info', '/chatter', expected=expected)
    assert (result.code, result.out, result.err) == (0, expected, '')
    # a relative name is expanded the way rcl does for a node in '/'
    assert run('topic', 'info', 'chatter').out == expected


def test_verbose_blocks(run: Run, graph: TokenGraph) -> None:
    pub_key = graph.node('talker').pub('/chatter', qos=QoSProfile(depth=7), type_hash=STRING_HASH)
    odd = QoSProfile(
        reliability=ReliabilityPolicy.BEST_EFFORT,
        durability=DurabilityPolicy.TRANSIENT_LOCAL,
        history=HistoryPolicy.KEEP_ALL,
        lifespan=Duration(seconds=10),
        deadline=Duration(nanoseconds=500),
        liveliness=LivelinessPolicy.MANUAL_BY_TOPIC,
        liveliness_lease_duration=Duration(seconds=2, nanoseconds=5),
    )
    sub_key = graph.node('listener', '/robot1').sub('/chatter', qos=odd, type_hash=STRING_HASH)
    expected = f'''Type: std_msgs/msg/String

Publisher count: 1

Node name: talker
Node namespace: /
Topic type: std_msgs/msg/String
Topic type hash: {STRING_HASH}
Endpoint type: PUBLISHER
GID: {dots(pub_key)}
QoS profile:
  Reliability: RELIABLE
  History (Depth): KEEP_LAST (7)
  Durability: VOLATILE
  Lifespan: Infinite
  Deadline: Infinite
  Liveliness: AUTOMATIC
  Liveliness lease duration: Infinite

Subscription count: 1

Node name: listener
Node namespace: /robot1
Topic type: std_msgs/msg/String
Topic type hash: {STRING_HASH}
Endpoint type: SUBSCRIPTION
GID: {dots(sub_key)}
QoS profile:
  Reliability: BEST_EFFORT
  History (Depth): KEEP_ALL
  Durability: TRANSIENT_LOCAL
  Lifespan: 10000000000 nanoseconds
  Deadline: 500 nanoseconds
  Liveliness: MANUAL_BY_TOPIC
  Liveliness lease duration: 2000000005 nanoseconds

'''
    result = settle(run, 'topic', 'info', '-v', '/chatter', expected=expected)
    assert (result.code, result.out, result.err) == (0, expected, '')
    assert run('topic', 'info', '/chatter', '--verbose').out == expected
    # 16 bytes, dotted lower-case hex
    assert len(dots(pub_key).split('.')) == 16 and dots(pub_key) != dots(sub_key)


def test_verbose_with_no_endpoints_of_one_kind(run: Run, graph: TokenGraph) -> None:
    graph.node('listener').sub('/lonely', type_hash=STRING_HASH)
    result = settle(
        run, 'topic', 'info', '/lonely', '-v', until=lambda out: 'Subscription count: 1' in out
    )
    assert result.out.startswith(
        'Type: std_msgs/msg/String\n\nPublisher count: 0\n\n'
        'Subscription count: 1\n\nNode name: listener\n'
    )
    assert result.out.endswith('Liveliness lease duration: Infinite\n\n')


def test_several_types_print_as_a_list(run: Run, graph: TokenGraph) -> None:
    node = graph.node('mixer')
    node.pub('/mixed', 'std_msgs/msg/Int32')
    node.pub('/mixed', STRING)
    expected = (
        "Type: ['std_msgs/msg/Int32', 'std_msgs/msg/String']\n"
        'Publisher count: 2\nSubscription count: 0\n'
    )
    assert settle(run, 'topic', 'info', '/mixed', expected=expected).out == expected


def test_hidden_topics_need_no_flag(run: Run, graph: TokenGraph) -> None:
    graph.node('_hidden').pub('/_secret', 'std_msgs/msg/Int32')
    expected = 'Type: std_msgs/msg/Int32\nPublisher count: 1\nSubscription count: 0\n'
    assert settle(run, 'topic', 'info', '/_secret', expected=expected).out == expected


def test_unknown_topic(run: Run, graph: TokenGraph) -> None:
    result = run('topic', 'info', '/nope')
    assert (result.code, result.out, result.err) == (1, '', "Unknown topic '/nope'\n")
    relative = run('topic', 'info', 'nope')
    assert (relative.code, relative.err) == (1, "Unknown topic '/nope'\n")


def test_invalid_topic_name_is_one_line(run: Run, graph: TokenGraph) -> None:
    result = run('topic', 'info', '/bad name')
    assert result.code == 1 and result.out == ''
    assert result.err.count('\n') == 1 and "'/bad name'" in result.err


def test_real_publisher_and_subscriber(
    run: Run, processes: Any, monkeypatch: pytest.MonkeyPatch
) -> None:
    private_domain(monkeypatch)
    _, gids = start_node(processes, 'talker', '/robot1', f'pub:chatter:{STRING}:7')
    start_node(processes, 'listener', '/', f'sub:/robot1/chatter:{STRING}:10')
    result = settle(
        run,
        'topic',
        'info',
        '/robot1/chatter',
        '-v',
        until=lambda out: 'Subscription count: 1' in out and 'Publisher count: 1' in out,
    )
    assert result.code == 0
    pub_block, sub_block = result.out.split('Subscription count: 1\n\n')
    assert (
        pub_block
        == f'''Type: std_msgs/msg/String

Publisher count: 1

Node name: talker
Node namespace: /robot1
Topic type: std_msgs/msg/String
Topic type hash: {STRING_HASH}
Endpoint type: PUBLISHER
GID: {dotted(gids['/robot1/chatter'])}
QoS profile:
  Reliability: RELIABLE
  History (Depth): KEEP_LAST (7)
  Durability: VOLATILE
  Lifespan: Infinite
  Deadline: Infinite
  Liveliness: AUTOMATIC
  Liveliness lease duration: Infinite

'''
    )
    assert sub_block.startswith('Node name: listener\nNode namespace: /\n')
    assert '  History (Depth): KEEP_LAST (10)\n' in sub_block
