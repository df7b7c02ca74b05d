"""`action send_goal`: output against an alien server, rejection, bad input, the server
timeout, and Ctrl-C canceling a running goal of the demo server."""

from __future__ import annotations

import re
import signal
import threading
import time
from collections.abc import Callable
from typing import Any

from tests.action.alien import AlienFibonacciServer
from tests.cli.conftest import run_process

FIB = 'example_interfaces/action/Fibonacci'


def test_send_goal_with_feedback(
    run: Callable[..., Any], alien_server: AlienFibonacciServer
) -> None:
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
        'Goal finished with status: SUCCEEDED\n'
    )
    assert alien_server.requests[:2] == ['send_goal', 'get_result']
    # the short type form works too, and without -f no feedback is printed
    quiet = run('action', 'send_goal', 'alien_fib', 'example_interfaces/Fibonacci', 'order: 1')
    assert quiet.code == 0 and 'Feedback' not in quiet.out
    assert quiet.out.endswith(
        'Result:\n    sequence:\n- 0\n- 1\n\nGoal finished with status: SUCCEEDED\n'
    )


def test_rejected_goal(run: Callable[..., Any], alien_server: AlienFibonacciServer) -> None:
    result = run('action', 'send_goal', '/alien_fib', FIB, '{order: -1}')
    assert (result.code, result.err) == (0, '')
    assert result.out.endswith('Sending goal:\n     order: -1\n\nGoal was rejected.\n')
    assert alien_server.requests == ['send_goal']


def test_bad_input(run: Callable[..., Any]) -> None:
    for bad_type in ('nope/action/Nope', 'example_interfaces/msg/String', 'Fibonacci'):
        result = run('action', 'send_goal', '/fib', bad_type, '{}')
        assert (result.code, result.out, result.err) == (
            1,
            '',
            'The passed action type is invalid\n',
        )
    result = run('action', 'send_goal', '/fib', FIB, '{ordr: 1}')
    assert result.code == 1 and result.out == ''
    assert result.err.startswith('Failed to populate message fields: ')
    assert 'ordr' in result.err and len(result.err.splitlines()) == 1
    result = run('action', 'send_goal', '/fib', FIB, '{order: 1.5}')
    assert (result.code, result.err) == (
        1,
        "Failed to populate message fields: field 'order' is an integer (int32); 1.5 is not one\n",
    )
    result = run('action', 'send_goal', '/fib', FIB, '{order: [1}')
    assert (result.code, result.err) == (
        1,
        "Failed to populate message fields: invalid YAML: expected ',' or ']', but got '}' "
        '(line 1, column 11)\n',
    )


def test_timeout_waiting_for_server(run: Callable[..., Any], ros_router: str) -> None:
    started = time.monotonic()
    result = run('action', 'send_goal', '/nobody_serves', FIB, '{order: 1}', '--timeout', '0.5')
    assert time.monotonic() - started < 10
    assert result.code == 1
    assert result.out == 'Waiting for an action server to become available...\n'
    assert result.err == "No action server for '/nobody_serves' after 0.5 s\n"


class Lines:
    """Everything a child writes to one pipe, read by a thread as it comes, so waiting for a
    line never misses one already in the pipe's buffer."""

    def __init__(self, stream: Any) -> None:
        self.lines: list[str] = []
        self._cond = threading.Condition()
        self._thread = threading.Thread(target=self._read, args=(stream,), daemon=True)
        self._thread.start()

    def _read(self, stream: Any) -> None:
        for line in iter(stream.readline, ''):
            with self._cond:
                self.lines.append(line)
                self._cond.notify_all()

    def wait_for(self, text: str, timeout: float) -> None:
        with self._cond:
            assert self._cond.wait_for(lambda: any(text in line for line in self.lines), timeout), (
                self.lines
            )

    def all(self, timeout: float) -> str:
        """The whole output, once the pipe closed (the child exited)."""
        self._thread.join(timeout)
        return ''.join(self.lines)


def test_ctrl_c_cancels_the_goal(processes: Any) -> None:
    server = processes.cli('run', 'action_tutorials_py', 'fibonacci_action_server')
    server_log = Lines(server.stderr)
    proc = processes.cli(
        'action',
        'send_goal',
        '-f',
        'fibonacci',
        'action_tutorials_interfaces/action/Fibonacci',
        '{order: 30}',
    )
    out = Lines(proc.stdout)
    out.wait_for('Feedback:', timeout=30)
    proc.send_signal(signal.SIGINT)
    assert proc.wait(timeout=20) == 2
    assert out.all(timeout=5).endswith('Canceling goal...\nGoal canceled.\n'), out.lines
    # the server saw the cancel and ended the goal as canceled
    server_log.wait_for('Goal canceled', timeout=20)
    assert any('Received cancel request' in line for line in server_log.lines)


def test_send_goal_runs_as_a_process(alien_server: AlienFibonacciServer) -> None:
    result = run_process('action', 'send_goal', '/alien_fib', FIB, '--stdin', stdin='order: 2')
    assert result.code == 0, result.err
    assert result.out.endswith('Goal finished with status: SUCCEEDED\n')


def test_server_gone_mid_goal(processes: Any, alien_server: AlienFibonacciServer) -> None:
    proc = processes.cli('action', 'send_goal', '/alien_fib', FIB, '{order: 1000}')
    out = Lines(proc.stdout)
    out.wait_for('Goal accepted', timeout=30)
    alien_server.close()
    assert proc.wait(timeout=20) == 1
    assert 'Canceling' not in out.all(timeout=5)
    err = proc.stderr.read()
    assert err.startswith('Exception while getting result: ') and len(err.splitlines()) == 1
