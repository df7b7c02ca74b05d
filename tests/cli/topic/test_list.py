"""`topic list` against hand-made tokens (exact output) and real node processes."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import pytest

from ros2lite.qos import QoSProfile

from ..graph_helpers import STRING, TokenGraph, private_domain, settle, start_node

Run = Callable[..., Any]


@pytest.fixture
def graph(ros_router: str, monkeypatch: pytest.MonkeyPatch) -> Any:
    """/robot1/talker pubs /robot1/chatter and subs /other; /listener subs /robot1/chatter;
    /_hidden_node pubs the hidden /_secret; two types on /mixed."""
    with TokenGraph(private_domain(monkeypatch)) as g:
        talker = g.node('talker', '/robot1')
        talker.pub('/robot1/chatter', qos=QoSProfile(depth=7))
        talker.sub('/other')
        listener = g.node('listener')
        listener.sub('/robot1/chatter')
        g.node('listener2').sub('/robot1/chatter')
        g.node('_hidden_node').pub('/_secret', 'std_msgs/msg/Int32')
        mixed = g.node('mixer')
        mixed.pub('/mixed', 'std_msgs/msg/Int32')
        mixed.pub('/mixed', STRING)
        mixed.pub('/mixed', STRING)
        g.node('other_ns', '/a/_private').pub('/a/_private/data', STRING)
        yield g


def test_plain_list_is_sorted_and_hides_hidden_names(run: Run, graph: TokenGraph) -> None:
    expected = '/mixed\n/other\n/robot1/chatter\n'
    result = settle(run, 'topic', 'list', expected=expected)
    assert (result.code, result.out, result.err) == (0, expected, '')


def test_show_types(run: Run, graph: TokenGraph) -> None:
    expected = (
        '/mixed [std_msgs/msg/Int32, std_msgs/msg/String]\n'
        '/other [std_msgs/msg/String]\n'
        '/robot1/chatter [std_msgs/msg/String]\n'
    )
    result = settle(run, 'topic', 'list', '-t', expected=expected)
    assert (result.code, result.out) == (0, expected)
    assert run('topic', 'list', '--show-types').out == expected


def test_count(run: Run, graph: TokenGraph) -> None:
    result = settle(run, 'topic', 'list', '-c', expected='3\n')
    assert (result.code, result.out) == (0, '3\n')
    assert run('topic', 'list', '--count-topics').out == '3\n'
    assert run('topic', 'list', '--count').out == '3\n'
    assert run('topic', 'list', '-c', '--include-hidden-topics').out == '5\n'
    # -c wins over -t and -v, as in ros2cli
    assert run('topic', 'list', '-c', '-t', '-v').out == '3\n'


def test_include_hidden_topics_on_verb_or_group(run: Run, graph: TokenGraph) -> None:
    expected = '/_secret\n/a/_private/data\n/mixed\n/other\n/robot1/chatter\n'
    result = settle(run, 'topic', 'list', '--include-hidden-topics', expected=expected)
    assert result.out == expected
    assert run('topic', 'list', '-a').out == expected
    assert run('topic', 'list', '--all').out == expected
    assert run('topic', '--include-hidden-topics', 'list').out == expected


def test_verbose(run: Run, graph: TokenGraph) -> None:
    expected = (
        'Published topics:\n'
        ' * /mixed [std_msgs/msg/Int32, std_msgs/msg/String] 3 publishers\n'
        ' * /robot1/chatter [std_msgs/msg/String] 1 publisher\n'
        '\n'
        'Subscribed topics:\n'
        ' * /other [std_msgs/msg/String] 1 subscriber\n'
        ' * /robot1/chatter [std_msgs/msg/String] 2 subscribers\n'
        '\n'
    )
    result = settle(run, 'topic', 'list', '-v', expected=expected)
    assert (result.code, result.out, result.err) == (0, expected, '')
    # -v ignores -t, as ros2cli does
    assert run('topic', 'list', '-v', '-t').out == expected
    hidden = run('topic', 'list', '--verbose', '-a').out
    assert ' * /_secret [std_msgs/msg/Int32] 1 publisher\n' in hidden


def test_strategy_options_are_accepted(run: Run, graph: TokenGraph) -> None:
    expected = '/mixed\n/other\n/robot1/chatter\n'
    settle(run, 'topic', 'list', expected=expected)
    for extra in (['--no-daemon'], ['--spin-time', '2'], ['-s'], ['--use-sim-time']):
        result = run('topic', 'list', *extra)
        assert (result.code, result.out) == (0, expected), extra


def test_topics_disappear_with_their_tokens(run: Run, graph: TokenGraph) -> None:
    node = graph.node('short_lived')
    key = node.pub('/temporary')
    settle(run, 'topic', 'list', expected='/mixed\n/other\n/robot1/chatter\n/temporary\n')
    graph.undeclare(key)
    expected = '/mixed\n/other\n/robot1/chatter\n'
    assert settle(run, 'topic', 'list', expected=expected).out == expected


def test_empty_graph_prints_nothing(
    run: Run, ros_router: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    private_domain(monkeypatch)
    for args in (['topic', 'list'], ['topic', 'list', '-t'], ['topic', 'list', '-v']):
        result = run(*args)
        assert (result.code, result.out, result.err) == (0, '', '')
    assert run('topic', 'list', '-c').out == '0\n'


def test_real_node_processes(run: Run, processes: Any, monkeypatch: pytest.MonkeyPatch) -> None:
    private_domain(monkeypatch)
    start_node(
        processes,
        'talker',
        '/robot1',
        f'pub:chatter:{STRING}:7',
        'sub:/numbers:std_msgs/msg/Int32:10',
    )
    start_node(processes, 'listener', '/', f'sub:/robot1/chatter:{STRING}:10')

    # ros2lite nodes add their own built-in topics (e.g. /rosout); only ours are asserted here
    def ours(out: str) -> list[str]:
        return [ln for ln in out.splitlines() if 'chatter' in ln or 'numbers' in ln]

    want = ['/numbers [std_msgs/msg/Int32]', '/robot1/chatter [std_msgs/msg/String]']
    result = settle(run, 'topic', 'list', '-t', until=lambda out: ours(out) == want)
    assert result.code == 0 and ours(result.out) == want
    verbose = run('topic', 'list', '-v').out
    assert ' * /robot1/chatter [std_msgs/msg/String] 1 publisher\n' in verbose
    assert ' * /robot1/chatter [std_msgs/msg/String] 1 subscriber\n' in verbose
    assert ' * /numbers [std_msgs/msg/Int32] 1 subscriber\n' in verbose
    assert '/numbers' not in verbose.split('Subscribed topics:')[0]
    # the same answer from a separate process
    from ..conftest import run_process

    assert ours(run_process('topic', 'list', '-t').out) == want


def test_graph_verbs_stay_light(ros_router: str) -> None:
    """No YAML, rich, MCAP or type system for graph queries: they only read tokens."""
    import subprocess
    import sys

    code = (
        'import sys\nfrom ros2lite.cli.main import main\n'
        "for args in (['topic', 'list', '-v'], ['topic', 'info', '-v', '/x'],\n"
        "             ['topic', 'type', '/x'], ['topic', 'find', 'a/msg/B'],\n"
        "             ['node', 'list'], ['node', 'info', '/x']):\n"
        '    main(args)\n'
        "print('heavy:', sorted(m for m in sys.modules if m.split('.')[0] in "
        "('yaml', 'rich', 'mcap') or m.startswith('ros2lite.interfaces')))"
    )
    out = subprocess.run(
        [sys.executable, '-c', code], capture_output=True, text=True, timeout=60
    ).stdout
    assert out.splitlines()[-1] == 'heavy: []'
