"""A big graph: 100 nodes and 1000 endpoints declared as tokens from one bare Zenoh session.

Every topic, type and node must come back, none twice and none missing: the graph query has
to collect all ~1100 replies (a default-sized reply channel stalls around 300).
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from typing import Any

import pytest

from ros2lite.transport.keys import EntityKind

from .conftest import run_process
from .graph_helpers import TokenGraph, private_domain, settle

Run = Callable[..., Any]

NODES = 100
PER_NODE = 10  # 5 publishers + 5 subscriptions
TYPES = ('std_msgs/msg/String', 'std_msgs/msg/Int32')


def topic(n: int, i: int) -> str:
    return f'/scale/t{n % NODES:03d}_{i}'


def node_name(n: int) -> tuple[str, str]:
    return f'/ns_{n % 10}', f'node_{n:03d}'


@pytest.fixture(scope='module')
def big_graph(ros_router: str) -> Iterator[TokenGraph]:
    with pytest.MonkeyPatch.context() as mp, TokenGraph(private_domain(mp)) as g:
        for n in range(NODES):
            namespace, name = node_name(n)
            node = g.node(name, namespace)
            for i in range(PER_NODE // 2):
                node.endpoint(EntityKind.PUBLISHER, topic(n, i), TYPES[i % 2])
                node.endpoint(EntityKind.SUBSCRIPTION, topic(n + 1, i), TYPES[i % 2])
        assert len(g._tokens) == NODES * (PER_NODE + 1)
        yield g


@pytest.fixture
def in_domain(big_graph: TokenGraph, monkeypatch: pytest.MonkeyPatch) -> TokenGraph:
    monkeypatch.setenv('ROS_DOMAIN_ID', str(big_graph.domain))
    return big_graph


EXPECTED_TOPICS = sorted(
    f'{topic(n, i)} [{TYPES[i % 2]}]' for n in range(NODES) for i in range(PER_NODE // 2)
)
EXPECTED_NODES = sorted('/'.join(node_name(n)) for n in range(NODES))


def test_topic_list_types(run: Run, in_domain: TokenGraph) -> None:
    expected = ''.join(line + '\n' for line in EXPECTED_TOPICS)
    assert len(EXPECTED_TOPICS) == 500
    result = settle(run, 'topic', 'list', '-t', expected=expected)
    assert (result.code, result.err) == (0, '')
    assert result.out == expected
    assert run('topic', 'list', '-c').out == '500\n'


def test_topic_list_in_a_separate_process(in_domain: TokenGraph) -> None:
    expected = ''.join(line + '\n' for line in EXPECTED_TOPICS)
    result = run_process('topic', 'list', '-t')
    assert (result.code, result.out, result.err) == (0, expected, '')


def test_topic_list_verbose_counts(run: Run, in_domain: TokenGraph) -> None:
    out = settle(run, 'topic', 'list', '-v', until=lambda o: o.count('\n') == 1004).out
    published, subscribed = out.split('\nSubscribed topics:\n')
    assert published.splitlines()[1:] == [f' * {t} 1 publisher' for t in EXPECTED_TOPICS]
    assert subscribed.splitlines() == [f' * {t} 1 subscriber' for t in EXPECTED_TOPICS] + ['']


def test_node_list(run: Run, in_domain: TokenGraph) -> None:
    expected = ''.join(name + '\n' for name in EXPECTED_NODES)
    result = settle(run, 'node', 'list', expected=expected)
    assert (result.code, result.out, result.err) == (0, expected, '')
    assert run('node', 'list', '-c').out == '100\n'
    assert run_process('node', 'list').out == expected


def test_find_and_info_at_scale(run: Run, in_domain: TokenGraph) -> None:
    strings = [t.split(' ')[0] for t in EXPECTED_TOPICS if t.endswith('String]')]
    result = settle(run, 'topic', 'find', TYPES[0], expected=''.join(s + '\n' for s in strings))
    assert len(strings) == 300 and result.out.count('\n') == 300
    info = run('topic', 'info', topic(42, 3))
    assert info.out == 'Type: std_msgs/msg/Int32\nPublisher count: 1\nSubscription count: 1\n'
    node = run('node', 'info', '/ns_2/node_042').out
    assert node.split('  Publishers:\n')[1].split('  Service Servers:')[0] == ''.join(
        f'    {topic(42, i)}: {TYPES[i % 2]}\n' for i in range(5)
    )
    assert node.split('  Subscribers:\n')[1].split('  Publishers:')[0] == ''.join(
        f'    {topic(43, i)}: {TYPES[i % 2]}\n' for i in range(5)
    )
