"""`action list` against an alien server: names, types, counts, hidden actions."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from tests.action.alien import AlienFibonacciServer
from tests.spinning import wait_until


def test_list(
    run: Callable[..., Any], alien_server: AlienFibonacciServer, alien_session: Any
) -> None:
    import os

    hidden = AlienFibonacciServer(
        alien_session,
        int(os.environ['ROS_DOMAIN_ID']),
        action='ns/_hidden_fib',
        node='alien_hidden',
    )
    try:
        wait_until(lambda: '/ns/_hidden_fib' in run('action', 'list', '-a').out, timeout=15)
        listed = run('action', 'list')
        assert listed.code == 0 and listed.out == '/alien_fib\n'
        assert (
            run('action', 'list', '-t').out == '/alien_fib [example_interfaces/action/Fibonacci]\n'
        )
        assert run('action', 'list', '-c').out == '1\n'
        assert run('action', 'list', '--all', '--count-actions').out == '2\n'
        assert (
            run('action', 'list', '--include-hidden-actions').out == '/alien_fib\n/ns/_hidden_fib\n'
        )
    finally:
        hidden.close()
