"""`action type`: the type of a known action; silent exit 1 otherwise."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from tests.action.alien import AlienFibonacciServer
from tests.spinning import wait_until


def test_type(run: Callable[..., Any], alien_server: AlienFibonacciServer) -> None:
    wait_until(lambda: run('action', 'type', '/alien_fib').code == 0, timeout=15)
    assert run('action', 'type', '/alien_fib').out == 'example_interfaces/action/Fibonacci\n'
    assert run('action', 'type', 'alien_fib').out == 'example_interfaces/action/Fibonacci\n'
    unknown = run('action', 'type', '/nope')
    assert (unknown.code, unknown.out) == (1, '')
    assert unknown.err == "Unknown action '/nope' (not in the graph now)\n"
