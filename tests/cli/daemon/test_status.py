"""`daemon status`: ros2cli's line, then which router serves the endpoint."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

from ros2lite import daemon
from ros2lite.daemon.control import daemon_pid

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


def test_a_secured_router_is_called_secured_not_frozen(private: Private, tmp_path: Path) -> None:
    """A daemon listening with TLS and client certificates, asked by a shell without an
    enclave (at its tls/ endpoint, or at tcp/ on the same port by mistake), and by one with
    an enclave of the same keystore: said to be there and secured, with what can be seen."""
    keystore = tmp_path / 'ks'
    for args in (('create_keystore', str(keystore)), ('create_enclave', str(keystore), '/me')):
        assert run_process('security', *args).code == 0
    port = private.endpoint.rpartition(':')[2]
    tls = f'tls/127.0.0.1:{port}'
    secured = {
        **private.env,
        'ROS2LITE_ROUTER': tls,
        'ROS_SECURITY_ENABLE': 'true',
        'ROS_SECURITY_STRATEGY': 'Enforce',
        'ROS_SECURITY_KEYSTORE': str(keystore),
        'ROS_SECURITY_ENCLAVE_OVERRIDE': '/me',
    }
    started = run_process('daemon', 'start', env=secured)
    assert (started.code, started.out) == (0, 'The daemon has been started\n'), started.err
    pid = daemon_pid(tls)  # the fixture points this process at the same runtime dir
    try:
        inside = run_process('daemon', 'status', env=secured)
        assert (inside.code, inside.err) == (0, '')
        assert inside.out.startswith(
            'The daemon is running\n'
            f'Serving {tls} (ros2lite daemon, pid {pid}, secured: TLS with client certificates)\n'
            'Connected sessions: '
        )
        outside = run_process('daemon', 'status', env={**private.env, 'ROS2LITE_ROUTER': tls})
        assert (outside.code, outside.err) == (0, '')
        assert outside.out == (
            'The daemon is running\n'
            f'Serving {tls} (ros2lite daemon, pid {pid}, secured: TLS with client certificates)\n'
            f'The ros2lite daemon (pid {pid}) at {tls} is secured (TLS with client '
            'certificates); this process runs unsecured, so it sees that the router is there '
            f'but not its sessions or graph: to join, use {tls} with ROS_SECURITY_ENABLE=true, '
            'ROS_SECURITY_KEYSTORE and an enclave (ROS_SECURITY_ENCLAVE_OVERRIDE or --ros-args '
            '--enclave)\n'
        )
        assert 'frozen' not in outside.out
        plain = run_process('daemon', 'status', env=private.env)  # tcp/ at the same port
        assert plain.out.startswith(
            'The daemon is running\n'
            f'Serving {private.endpoint} (a Zenoh router not started by ros2lite, secured: '
            f'TLS with client certificates)\nA Zenoh router at {private.endpoint} is secured'
        )
        assert f'use {tls} with ROS_SECURITY_ENABLE=true' in plain.out
        # a graph verb there gets the same words, in one line
        listed = run_process('topic', 'list', env=private.env)
        assert (listed.code, listed.out) == (1, '')
        assert listed.err.startswith(f'A Zenoh router at {private.endpoint} is secured')
        assert listed.err.count('\n') == 1
    finally:
        assert run_process('daemon', 'stop', env=secured).code == 0
