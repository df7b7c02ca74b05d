"""`node info`: sections, indentation and blank lines exactly as ros2cli prints them."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import pytest

from ..graph_helpers import STRING, TokenGraph, private_domain, settle, start_node

Run = Callable[..., Any]

FIB = 'example_interfaces/action/Fibonacci'

EMPTY = '''{name}
  Subscribers:

  Publishers:

  Service Servers:

  Service Clients:

  Action Servers:

  Action Clients:

'''


@pytest.fixture
def graph(ros_router: str, monkeypatch: pytest.MonkeyPatch) -> Any:
    with TokenGraph(private_domain(monkeypatch)) as g:
        server = g.node('fib_server', '/demo')
        server.action_server('/fibonacci', FIB)
        server.server('/demo/fib_server/get_parameters', 'rcl_interfaces/srv/GetParameters')
        server.server(
            '/demo/fib_server/describe_parameters', 'rcl_interfaces/srv/DescribeParameters'
        )
        server.client('/add_two_ints', 'example_interfaces/srv/AddTwoInts')
        server.pub('/rosout', 'rcl_interfaces/msg/Log')
        server.pub('/chatter')
        server.pub('/chatter', 'std_msgs/msg/Int32')
        server.sub('/_hidden_input')
        server.sub('/input')
        client = g.node('fib_client')
        client.action_client('/fibonacci', FIB)
        client.action_client('/other/_private_action', FIB)
        g.node('idle')
        g.node('_hidden_node').pub('/chatter')
        yield g


SERVER_INFO = '''/demo/fib_server
  Subscribers:
    /input: std_msgs/msg/String
  Publishers:
    /chatter: std_msgs/msg/Int32, std_msgs/msg/String
    /rosout: rcl_interfaces/msg/Log
  Service Servers:
    /demo/fib_server/describe_parameters: rcl_interfaces/srv/DescribeParameters
    /demo/fib_server/get_parameters: rcl_interfaces/srv/GetParameters
  Service Clients:
    /add_two_ints: example_interfaces/srv/AddTwoInts
  Action Servers:
    /fibonacci: example_interfaces/action/Fibonacci
  Action Clients:

'''


def test_action_server_node(run: Run, graph: TokenGraph) -> None:
    result = settle(run, 'node', 'info', '/demo/fib_server', expected=SERVER_INFO)
    assert (result.code, result.out, result.err) == (0, SERVER_INFO, '')


def test_action_client_node(run: Run, graph: TokenGraph) -> None:
    expected = '''/fib_client
  Subscribers:

  Publishers:

  Service Servers:

  Service Clients:

  Action Servers:

  Action Clients:
    /fibonacci: example_interfaces/action/Fibonacci
'''
    result = settle(run, 'node', 'info', '/fib_client', expected=expected)
    assert (result.code, result.out, result.err) == (0, expected, '')


def test_include_hidden(run: Run, graph: TokenGraph) -> None:
    expected = '''/fib_client
  Subscribers:
    /fibonacci/_action/feedback: example_interfaces/action/Fibonacci_FeedbackMessage
    /fibonacci/_action/status: action_msgs/msg/GoalStatusArray
    /other/_private_action/_action/feedback: example_interfaces/action/Fibonacci_FeedbackMessage
    /other/_private_action/_action/status: action_msgs/msg/GoalStatusArray
  Publishers:

  Service Servers:

  Service Clients:
    /fibonacci/_action/cancel_goal: action_msgs/srv/CancelGoal
    /fibonacci/_action/get_result: example_interfaces/action/Fibonacci_GetResult
    /fibonacci/_action/send_goal: example_interfaces/action/Fibonacci_SendGoal
    /other/_private_action/_action/cancel_goal: action_msgs/srv/CancelGoal
    /other/_private_action/_action/get_result: example_interfaces/action/Fibonacci_GetResult
    /other/_private_action/_action/send_goal: example_interfaces/action/Fibonacci_SendGoal
  Action Servers:

  Action Clients:
    /fibonacci: example_interfaces/action/Fibonacci
    /other/_private_action: example_interfaces/action/Fibonacci
'''
    result = settle(run, 'node', 'info', '/fib_client', '--include-hidden', expected=expected)
    assert (result.code, result.out, result.err) == (0, expected, '')
    server = run('node', 'info', '/demo/fib_server', '--include-hidden').out
    assert '    /_hidden_input: std_msgs/msg/String\n' in server
    assert (
        '    /fibonacci/_action/feedback: '
        'example_interfaces/action/Fibonacci_FeedbackMessage\n' in server
    )


def test_node_without_endpoints(run: Run, graph: TokenGraph) -> None:
    expected = EMPTY.format(name='/idle')
    assert settle(run, 'node', 'info', '/idle', expected=expected).out == expected
    # a relative name means the node in '/'
    assert run('node', 'info', 'idle').out == expected


def test_hidden_node_needs_include_hidden(run: Run, graph: TokenGraph) -> None:
    settle(run, 'node', 'info', '/idle', until=bool)
    hidden = run('node', 'info', '/_hidden_node')
    assert (hidden.code, hidden.out, hidden.err) == (1, '', "Unable to find node '/_hidden_node'\n")
    shown = run('node', 'info', '/_hidden_node', '--include-hidden')
    assert shown.code == 0
    assert shown.out.startswith(
        '/_hidden_node\n  Subscribers:\n\n  Publishers:\n    /chatter: std_msgs/msg/String\n'
    )


def test_unknown_node(run: Run, graph: TokenGraph) -> None:
    for name in ('/nope', '/demo', '/fib_server'):
        result = run('node', 'info', name)
        assert (result.code, result.out, result.err) == (1, '', f"Unable to find node '{name}'\n")


def test_shared_name_warning(run: Run, graph: TokenGraph) -> None:
    twin = graph.node('fib_server', '/demo', zid='fedcba9876543210fedcba9876543210')
    twin.pub('/twin_only')
    settle(run, 'node', 'list', '-c', expected='4\n')
    result = run('node', 'info', '/demo/fib_server')
    assert result.code == 0
    assert result.err == (
        'There are 2 nodes in the graph with the exact name '
        '"/demo/fib_server". You are seeing information about only one of '
        'them.\n'
    )
    # one instance is described, never a merge of both
    twin_info = EMPTY.format(name='/demo/fib_server').replace(
        '  Publishers:\n\n', '  Publishers:\n    /twin_only: std_msgs/msg/String\n'
    )
    assert result.out in (SERVER_INFO, twin_info)


def test_real_node_process(run: Run, processes: Any, monkeypatch: pytest.MonkeyPatch) -> None:
    private_domain(monkeypatch)
    start_node(
        processes,
        'talker',
        '/robot1',
        f'pub:chatter:{STRING}:7',
        'sub:/numbers:std_msgs/msg/Int32:10',
        f'sub:/_internal:{STRING}:10',
    )
    result = settle(
        run,
        'node',
        'info',
        '/robot1/talker',
        until=lambda out: '/numbers' in out and '/robot1/chatter' in out,
    )
    assert result.code == 0 and result.err == ''
    lines = result.out.splitlines()
    headings = [ln for ln in lines if not ln.startswith('    ')]
    assert headings[0] == '/robot1/talker'
    assert [h for h in headings[1:] if h] == [
        '  Subscribers:',
        '  Publishers:',
        '  Service Servers:',
        '  Service Clients:',
        '  Action Servers:',
        '  Action Clients:',
    ]
    subs = lines[lines.index('  Subscribers:') + 1 : lines.index('  Publishers:')]
    pubs = lines[lines.index('  Publishers:') + 1 : lines.index('  Service Servers:')]
    assert subs == ['    /numbers: std_msgs/msg/Int32']
    assert '    /robot1/chatter: std_msgs/msg/String' in pubs
    assert result.out.endswith('  Action Servers:\n\n  Action Clients:\n\n')
