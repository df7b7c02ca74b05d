"""`daemon stop`, and a whole start/status/stop cycle through the CLI."""

from __future__ import annotations

from ros2lite import daemon

from ..conftest import run_process
from .conftest import Private


def test_stop_when_not_running(private: Private) -> None:
    result = run_process('daemon', 'stop', env=private.env)
    assert (result.code, result.out, result.err) == (0, 'The daemon is not running\n', '')


def test_cycle(private: Private) -> None:
    steps = [
        ('status', 'The daemon is not running'),
        ('start', 'The daemon has been started'),
        ('status', 'The daemon is running'),
        ('stop', 'The daemon has been stopped'),
        ('status', 'The daemon is not running'),
        ('stop', 'The daemon is not running'),
    ]
    for verb, first_line in steps:
        result = run_process('daemon', verb, env=private.env)
        assert result.code == 0, (verb, result.err)
        assert result.out.splitlines()[0] == first_line, verb
    assert not daemon.router_answers(private.endpoint)
    assert list(private.runtime.glob('ros2lite/*.pid')) == []


def test_stop_says_who_was_connected(private: Private) -> None:
    from ros2lite.transport.open import open_session

    daemon.start(private.endpoint)
    client = open_session(private.endpoint)  # a CLI verb or a client-mode node
    try:
        result = run_process('daemon', 'stop', env=private.env)
    finally:
        client.close()
    assert (result.code, result.err) == (0, '')
    assert result.out == (
        'The daemon has been stopped\n'
        '1 session was connected to it\n'
        '1 client session (CLI verbs, client-mode nodes) lost the connection '
        'until a router runs again\n'
    )
