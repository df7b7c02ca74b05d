"""`action send_goal` to a name served with another type says so instead of waiting."""

from __future__ import annotations

from tests.action.alien import AlienFibonacciServer
from tests.cli.conftest import run_process
from tests.spinning import wait_until


def test_send_goal_says_the_type_the_action_has(alien_server: AlienFibonacciServer) -> None:
    wait_until(lambda: run_process('action', 'type', '/alien_fib').code == 0, timeout=15)
    result = run_process(
        'action',
        'send_goal',
        '/alien_fib',
        'turtlesim/action/RotateAbsolute',
        '{theta: 1.0}',
        '--timeout',
        '3',
    )
    assert result.code == 1
    assert (
        "WARNING: action '/alien_fib' is served as example_interfaces/action/Fibonacci, not "
        'turtlesim/action/RotateAbsolute' in result.err
    )
