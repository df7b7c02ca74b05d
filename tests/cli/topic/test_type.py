"""`topic type`: one type per line; an unknown topic exits 1 without a word, as in ros2cli."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import pytest

from ..graph_helpers import STRING, TokenGraph, private_domain, settle

Run = Callable[..., Any]


@pytest.fixture
def graph(ros_router: str, monkeypatch: pytest.MonkeyPatch) -> Any:
    with TokenGraph(private_domain(monkeypatch)) as g:
        g.node('talker', '/robot1').pub('/robot1/chatter')
        mixer = g.node('mixer')
        mixer.pub('/mixed', 'std_msgs/msg/Int32')
        mixer.sub('/mixed', STRING)
        g.node('_hidden').pub('/_secret', 'std_msgs/msg/Int32')
        yield g


def test_type(run: Run, graph: TokenGraph) -> None:
    result = settle(run, 'topic', 'type', '/robot1/chatter', expected='std_msgs/msg/String\n')
    assert (result.code, result.out, result.err) == (0, 'std_msgs/msg/String\n', '')
    assert run('topic', 'type', 'robot1/chatter').out == 'std_msgs/msg/String\n'


def test_several_types_one_per_line(run: Run, graph: TokenGraph) -> None:
    expected = 'std_msgs/msg/Int32\nstd_msgs/msg/String\n'
    assert settle(run, 'topic', 'type', '/mixed', expected=expected).out == expected


def test_unknown_is_exit_1_with_one_line_on_stderr(run: Run, graph: TokenGraph) -> None:
    settle(run, 'topic', 'type', '/mixed', until=bool)
    for name, why in (
        ('/nope', "Unknown topic '/nope' (not in the graph now)"),
        ('bad name', "topic name 'bad name' is invalid: must not contain characters other"),
        ('/robot1', "Unknown topic '/robot1' (not in the graph now)"),
    ):
        result = run('topic', 'type', name)
        assert (result.code, result.out) == (1, ''), name
        assert result.err.startswith(why) and result.err.count('\n') == 1, result.err


def test_hidden_topic_needs_the_group_flag(run: Run, graph: TokenGraph) -> None:
    result = settle(
        run, 'topic', '--include-hidden-topics', 'type', '/_secret', expected='std_msgs/msg/Int32\n'
    )
    assert (result.code, result.out) == (0, 'std_msgs/msg/Int32\n')
    assert run('topic', 'type', '/_secret').code == 1
