"""`action send_goal`: output against an alien server, rejection, bad input, the server
timeout, and Ctrl-C canceling a running goal of the demo server."""

from __future__ import annotations

import re
import signal
import subprocess
import sys
import time
from collections.abc import Callable
from typing import Any

from tests.action.alien import AlienFibonacciServer
from tests.cli.conftest import run_process

FIB = 'example_interfaces/action/Fibonacci'


def test_send_goal_with_feedback(run: Callable[..., Any],
                                 alien_server: AlienFibonacciServer) -> None:
    result = run('action', 'send_goal', '/alien_fib', FIB, '{order: 3}', '-f')
    assert result.code == 0, result.err
    goal_id = re.search(r'Goal accepted with ID: ([0-9a-f]{32})\n', result.out)
    assert goal_id is not None, result.out
    assert result.out == (
        'Waiting for an action server to become available...\n'
        'Sending goal:\n     order: 3\n\n'
        f'Goal accepted with ID: {goal_id[1]}\n\n'
        'Feedback:\n    sequence:\n- 0\n- 1\n- 1\n\n'
        'Feedback:\n    sequence:\n- 0\n- 1\n- 1\n- 2\n\n'
        'Result:\n    sequence:\n- 0\n- 1\n- 1\n- 2\n\n'
        'Goal finished with status: SUCCEEDED\n')
    assert alien_server.requests[:2] == ['send_goal', 'get_result']
    # the short type form works too, and without -f no feedback is printed
    quiet = run('action', 'send_goal', 'alien_fib', 'example_interfaces/Fibonacci', 'order: 1')
    assert quiet.code == 0 and 'Feedback' not in quiet.out
    assert quiet.out.endswith('Result:\n    sequence:\n- 0\n- 1\n\n'
                              'Goal finished with status: SUCCEEDED\n')


def test_rejected_goal(run: Callable[..., Any], alien_server: AlienFibonacciServer) -> None:
    result = run('action', 'send_goal', '/alien_fib', FIB, '{order: -1}')
    assert (result.code, result.err) == (0, '')
    assert result.out.endswith('Sending goal:\n     order: -1\n\nGoal was rejected.\n')
    assert alien_server.requests == ['send_goal']


def test_bad_input(run: Callable[..., Any]) -> None:
    for bad_type in ('nope/action/Nope', 'example_interfaces/msg/String', 'Fibonacci'):
        result = run('action', 'send_goal', '/fib', bad_type, '{}')
        assert (result.code, result.out, result.err) == (
            1, '', 'The passed action type is invalid\n')
    result = run('action', 'send_goal', '/fib', FIB, '{ordr: 1}')
    assert result.code == 1 and result.out == ''
    assert result.err.startswith('Failed to populate message fields: ')
    assert 'ordr' in result.err and len(result.err.splitlines()) == 1
    result = run('action', 'send_goal', '/fib', FIB, '{order: 1.5.}')
    assert result.code == 1 and result.err.startswith('Failed to populate message fields: ')


def test_timeout_waiting_for_server(run: Callable[..., Any], ros_router: str) -> None:
    started = time.monotonic()
    result = run('action', 'send_goal', '/nobody_serves', FIB, '{order: 1}', '--timeout', '0.5')
    assert time.monotonic() - started < 10
    assert result.code == 1
    assert result.out == 'Waiting for an action server to become available...\n'
    assert result.err == "No action server for '/nobody_serves' after 0.5 s\n"


def test_ctrl_c_cancels_the_goal(processes: Any) -> None:
    server = processes.cli('run', 'action_tutorials_py', 'fibonacci_action_server')
    proc = processes.start(
        [sys.executable, '-m', 'ros2lite', 'action', 'send_goal', '-f', 'fibonacci',
         'action_tutorials_interfaces/action/Fibonacci', '{order: 30}'],
        stdout=subprocess.PIPE)
    assert proc.stdout is not None
    lines = []
    deadline = time.monotonic() + 30
    while not lines or lines[-1] != 'Feedback:\n':
        assert time.monotonic() < deadline, lines
        line = proc.stdout.readline()
        assert line, lines
        lines.append(line)
    proc.send_signal(signal.SIGINT)
    out, _ = proc.communicate(timeout=20)
    assert proc.returncode == 2
    assert out.endswith('Canceling goal...\nGoal canceled.\n'), out
    _, err = processes.stop(server)
    assert 'Received cancel request' in err and 'Goal canceled' in err


def test_send_goal_runs_as_a_process(alien_server: AlienFibonacciServer) -> None:
    result = run_process('action', 'send_goal', '/alien_fib', FIB, '--stdin',
                         stdin='order: 2')
    assert result.code == 0, result.err
    assert result.out.endswith('Goal finished with status: SUCCEEDED\n')
