"""`action find`: the actions of one type."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from tests.action.alien import AlienFibonacciServer
from tests.spinning import wait_until


def test_find(run: Callable[..., Any], alien_server: AlienFibonacciServer) -> None:
    fib = 'example_interfaces/action/Fibonacci'
    wait_until(lambda: run('action', 'find', fib).out == '/alien_fib\n', timeout=15)
    assert run('action', 'find', fib, '-c').out == '1\n'
    other = run('action', 'find', 'action_tutorials_interfaces/action/Fibonacci')
    assert (other.code, other.out) == (0, '')
    assert run('action', 'find', 'nope/action/Nope', '--count-actions').out == '0\n'
