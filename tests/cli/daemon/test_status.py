"""`daemon status`: ros2cli's line, then which router serves the endpoint."""

from __future__ import annotations

import os
import subprocess
import sys

from ros2lite import daemon

from ..conftest import run_process
from .conftest import Private


def test_not_running(private: Private) -> None:
    result = run_process('daemon', 'status', env=private.env)
    assert (result.code, result.err) == (0, '')
    assert result.out == (
        f'The daemon is not running\nNo Zenoh router answers at {private.endpoint}\n'
    )


def test_running(private: Private) -> None:
    started = daemon.start(private.endpoint)
    result = run_process('daemon', 'status', env=private.env)
    assert (result.code, result.err) == (0, '')
    assert result.out == (
        'The daemon is running\n'
        f'Serving {private.endpoint} (ros2lite daemon, pid {started.pid})\n'
        'Connected sessions: 0\n'
    )


def test_foreign_router(private: Private) -> None:
    import zenoh

    from ros2lite.transport.config import router_config

    router = zenoh.open(router_config(private.endpoint, env={}))
    try:
        result = run_process('daemon', 'status', env=private.env)
        assert result.out == (
            'The daemon is running\n'
            f'Serving {private.endpoint} (a Zenoh router not started by '
            'ros2lite)\nConnected sessions: 0\n'
        )
        start = run_process('daemon', 'start', env=private.env)
        assert start.out == (
            'The daemon is already running\n'
            'A Zenoh router not started by ros2lite answers at '
            f'{private.endpoint}\n'
        )
        stop = run_process('daemon', 'stop', env=private.env)
        assert stop.out == (
            'The daemon is not running\n'
            f'A Zenoh router not started by ros2lite answers at '
            f'{private.endpoint}; not stopping it\n'
        )
        assert all(r.code == 0 for r in (result, start, stop))
        assert daemon.router_answers(private.endpoint)  # left alone
    finally:
        router.close()


# a node that prints its session id, then lives until killed
NODE = """
import time
import ros2lite
ctx = ros2lite.init([])
node = ros2lite.Node('status_probe')
print(ctx.zid, flush=True)
time.sleep(60)
"""


def test_sessions_and_their_nodes(private: Private) -> None:
    """A peer node and a client session are both listed, the node by name; the status
    command's own session is not counted."""
    from ros2lite.transport.open import open_session

    daemon.start(private.endpoint)
    node = subprocess.Popen(
        [sys.executable, '-c', NODE],
        stdout=subprocess.PIPE,
        text=True,
        env={**os.environ, **private.env},
    )
    try:
        assert node.stdout is not None
        node_zid = node.stdout.readline().strip()
        client = open_session(private.endpoint)  # e.g. a CLI verb, or zenoh tooling
        try:
            result = run_process('daemon', 'status', env=private.env)
        finally:
            client.close()
    finally:
        node.kill()
        node.wait()
    assert (result.code, result.err) == (0, '')
    lines = result.out.splitlines()
    assert lines[2] == 'Connected sessions: 2', result.out
    rows = sorted(line.split() for line in lines[3:])
    assert rows == [
        ['client', str(client.zid()), '(no', 'nodes)'],
        ['peer', node_zid, '/status_probe'],
    ]
