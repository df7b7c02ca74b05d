"""A Foxglove bridge under an enclave with security on says at start, in one line, that a
WebSocket client acts as that enclave and how to close the door (R5-F1b); unsecured, it
says nothing of the kind."""

from __future__ import annotations

from typing import Any

from tests.spinning import free_port
from tests.transport.test_security import environ, procs, secured, start_cli

__all__ = ['procs', 'secured']  # the fixtures, shared with the secured-graph tests

WARNING = 'security is on: any local user who reaches ws://127.0.0.1:'


def test_a_secured_bridge_says_who_its_clients_act_as(
    secured: dict[str, str], procs: list[Any]
) -> None:
    port = free_port()
    proc, lines = start_cli(
        [
            'run',
            'foxglove_bridge',
            'foxglove_bridge',
            '--ros-args',
            '--enclave',
            '/sec/talker',
            '-p',
            f'port:={port}',
        ],
        environ(secured),
    )
    procs.append(proc)
    lines.wait_for('Foxglove bridge listening on', timeout=30)
    line = lines.wait_for(WARNING)
    assert f'ws://127.0.0.1:{port} ' in line and 'as enclave /sec/talker;' in line
    assert 'firewall' in line and 'no bridge under an enclave' in line
    assert lines.text().count(WARNING) == 1, line


def test_an_unsecured_bridge_says_nothing_of_it(ros_router: str, procs: list[Any]) -> None:
    port = free_port()
    args = ['run', 'foxglove_bridge', 'foxglove_bridge', '--ros-args', '-p', f'port:={port}']
    proc, lines = start_cli(args, environ({}))
    procs.append(proc)
    lines.wait_for('Foxglove bridge listening on', timeout=30)
    assert WARNING not in lines.text()
