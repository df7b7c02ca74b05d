"""`node list`: sorted full names, hidden nodes with -a, the shared-name warning."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import pytest

from ..graph_helpers import STRING, TokenGraph, private_domain, settle, start_node

Run = Callable[..., Any]

WARNING = (
    'WARNING: Be aware that there are nodes in the graph that share an exact name, '
    'which can have unintended side effects.\n'
)


@pytest.fixture
def graph(ros_router: str, monkeypatch: pytest.MonkeyPatch) -> Any:
    with TokenGraph(private_domain(monkeypatch)) as g:
        g.node('talker')
        g.node('talker', '/robot1')
        g.node('listener', '/robot1/arm')
        g.node('_ros2cli_123')
        g.node('visible', '/_hidden_ns')  # only the node's own name decides, as in ros2cli
        g.node('a_first')
        yield g


def test_list_sorted_full_names(run: Run, graph: TokenGraph) -> None:
    expected = '/_hidden_ns/visible\n/a_first\n/robot1/arm/listener\n/robot1/talker\n/talker\n'
    result = settle(run, 'node', 'list', expected=expected)
    assert (result.code, result.out, result.err) == (0, expected, '')


def test_all_shows_hidden_nodes(run: Run, graph: TokenGraph) -> None:
    expected = (
        '/_hidden_ns/visible\n/_ros2cli_123\n/a_first\n/robot1/arm/listener\n'
        '/robot1/talker\n/talker\n'
    )
    assert settle(run, 'node', 'list', '-a', expected=expected).out == expected
    assert run('node', 'list', '--all').out == expected


def test_count(run: Run, graph: TokenGraph) -> None:
    assert settle(run, 'node', 'list', '-c', expected='5\n').out == '5\n'
    assert run('node', 'list', '--count-nodes').out == '5\n'
    assert run('node', 'list', '--count', '-a').out == '6\n'


def test_duplicate_names_warn_on_stderr(run: Run, graph: TokenGraph) -> None:
    # same name from "another process" (another session id) and from this one
    graph.node('talker', zid='0123456789abcdef0123456789abcdef').pub('/chatter')
    expected = (
        '/_hidden_ns/visible\n/a_first\n/robot1/arm/listener\n/robot1/talker\n/talker\n/talker\n'
    )
    result = settle(run, 'node', 'list', expected=expected)
    assert (result.code, result.out, result.err) == (0, expected, WARNING)
    # counts include every instance
    assert run('node', 'list', '-c').out == '6\n'


def test_node_known_only_from_an_endpoint_token(run: Run, graph: TokenGraph) -> None:
    # rmw_zenoh creates a node from its endpoint tokens even without an NN token
    from ros2lite.qos import QoSProfile
    from ros2lite.transport.keys import EntityKind, endpoint_token

    key = endpoint_token(
        graph.domain,
        graph.zid,
        900,
        901,
        EntityKind.PUBLISHER,
        '/',
        'ghost',
        '/chatter',
        STRING,
        'RIHS01_' + '0' * 64,
        QoSProfile(depth=10),
    )
    graph.declare(key)
    result = settle(run, 'node', 'list', until=lambda out: '/ghost\n' in out)
    assert '/ghost\n' in result.out and result.err == ''


def test_empty_graph(run: Run, ros_router: str, monkeypatch: pytest.MonkeyPatch) -> None:
    private_domain(monkeypatch)
    result = run('node', 'list')
    assert (result.code, result.out, result.err) == (0, '', '')
    assert run('node', 'list', '-c').out == '0\n'


def test_real_nodes_including_the_same_name_twice(
    run: Run, processes: Any, monkeypatch: pytest.MonkeyPatch
) -> None:
    private_domain(monkeypatch)
    start_node(processes, 'talker', '/robot1', f'pub:chatter:{STRING}:10')
    start_node(processes, 'talker', '/robot1', f'pub:chatter:{STRING}:10')
    start_node(processes, 'listener', '/', f'sub:/robot1/chatter:{STRING}:10')
    expected = '/listener\n/robot1/talker\n/robot1/talker\n'
    result = settle(run, 'node', 'list', expected=expected)
    assert (result.code, result.out, result.err) == (0, expected, WARNING)
