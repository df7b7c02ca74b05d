"""`topic find`: topics whose type list holds exactly the given type."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import pytest

from ..graph_helpers import STRING, TokenGraph, private_domain, settle

Run = Callable[..., Any]


@pytest.fixture
def graph(ros_router: str, monkeypatch: pytest.MonkeyPatch) -> Any:
    with TokenGraph(private_domain(monkeypatch)) as g:
        node = g.node('n')
        node.pub('/b_chatter')
        node.sub('/a_chatter')
        node.pub('/mixed', 'std_msgs/msg/Int32')
        node.pub('/mixed', STRING)
        node.pub('/count', 'std_msgs/msg/Int32')
        node.pub('/_hidden/chatter')
        node.server('/srv', 'std_srvs/srv/Empty')
        yield g


def test_find(run: Run, graph: TokenGraph) -> None:
    expected = '/a_chatter\n/b_chatter\n/mixed\n'
    result = settle(run, 'topic', 'find', STRING, expected=expected)
    assert (result.code, result.out, result.err) == (0, expected, '')
    assert run('topic', 'find', 'std_msgs/msg/Int32').out == '/count\n/mixed\n'


def test_count(run: Run, graph: TokenGraph) -> None:
    assert settle(run, 'topic', 'find', '-c', STRING, expected='3\n').out == '3\n'
    assert run('topic', 'find', STRING, '--count-topics').out == '3\n'
    assert run('topic', 'find', '-c', STRING, '--include-hidden-topics').out == '4\n'


def test_hidden(run: Run, graph: TokenGraph) -> None:
    expected = '/_hidden/chatter\n/a_chatter\n/b_chatter\n/mixed\n'
    assert (
        settle(run, 'topic', 'find', STRING, '--include-hidden-topics', expected=expected).out
        == expected
    )
    assert run('topic', '--include-hidden-topics', 'find', STRING).out == expected


def test_no_match(run: Run, graph: TokenGraph) -> None:
    settle(run, 'topic', 'find', STRING, until=bool)
    # exact match only: no prefixes, no service types
    for type_name in ('std_msgs/msg/Str', 'std_srvs/srv/Empty', 'nope/msg/Nope'):
        result = run('topic', 'find', type_name)
        assert (result.code, result.out, result.err) == (0, '', ''), type_name
        assert run('topic', 'find', '-c', type_name).out == '0\n'
