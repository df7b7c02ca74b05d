"""A listener that is not a Zenoh router (another program, or a frozen daemon): `topic list`
and `daemon start`/`status` say which, instead of 'start the daemon' / 'already running'."""

from __future__ import annotations

import os
import signal
import socket
import subprocess
import sys
from pathlib import Path

import pytest

from ros2lite import daemon
from ros2lite.daemon.errors import DaemonError


def _cli(endpoint: str, *args: str) -> subprocess.CompletedProcess[str]:
    env = dict(os.environ, ROS2LITE_ROUTER=endpoint)
    return subprocess.run(
        [sys.executable, '-m', 'ros2lite', *args],
        capture_output=True,
        text=True,
        timeout=60,
        env=env,
    )


def test_another_program_on_the_port(endpoint: str, runtime: Path) -> None:
    host, port = endpoint.split('/')[1].rsplit(':', 1)
    with socket.socket() as listener:
        listener.bind((host, int(port)))
        listener.listen(8)
        listed = _cli(endpoint, 'topic', 'list')
        assert listed.returncode == 1
        assert listed.stderr == (
            f'Something listens at {endpoint} but does not answer as a Zenoh router (a frozen '
            'router, or another program on that port): stop it, or choose another endpoint '
            '(ROS2LITE_ROUTER)\n'
        )
        with pytest.raises(DaemonError, match='does not answer as a Zenoh router'):
            daemon.start(endpoint)
        status = _cli(endpoint, 'daemon', 'status')
        assert status.stdout.startswith('The daemon is not answering\nSomething listens at')


def test_a_frozen_daemon(endpoint: str, runtime: Path) -> None:
    started = daemon.start(endpoint)
    assert started.started and started.pid is not None
    os.kill(started.pid, signal.SIGSTOP)
    try:
        listed = _cli(endpoint, 'topic', 'list')
        assert listed.returncode == 1
        assert listed.stderr.startswith(
            f'The ros2lite daemon (pid {started.pid}) listens at {endpoint} but does not answer '
            "as a Zenoh router (frozen or overloaded?); 'ros2lite daemon stop' ends it"
        ), listed.stderr
        start = _cli(endpoint, 'daemon', 'start')
        assert start.returncode == 1 and 'frozen or overloaded' in start.stderr
    finally:
        os.kill(started.pid, signal.SIGCONT)
    assert daemon.stop(endpoint).stopped
