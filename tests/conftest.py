"""Live-graph fixtures: one real Zenoh router per test session on a free loopback port, a
private ROS_DOMAIN_ID, and helpers to run node processes against it.

The router and domain are exported through os.environ, so the CLI (in-process or as a
subprocess) and every spawned node find them exactly as a user's shell would.
"""

from __future__ import annotations

import os
import random
import signal
import subprocess
import sys
from collections.abc import Iterator
from typing import Any

import pytest

from tests.spinning import free_port, wait_until

__all__ = ['free_port', 'wait_until']


@pytest.fixture(scope='session')
def ros_router() -> Iterator[str]:
    """A real router for the whole session; yields its endpoint."""
    import zenoh

    from ros2lite.transport.config import router_config

    saved = {
        k: os.environ.get(k)
        for k in (
            'ROS2LITE_ROUTER',
            'ROS_DOMAIN_ID',
            'ZENOH_CONFIG_OVERRIDE',
            'ZENOH_SESSION_CONFIG_URI',
            'ZENOH_ROUTER_CONFIG_URI',
            'XDG_RUNTIME_DIR',
            'ROS2LITE_NO_DAEMON',
        )
    }
    endpoint = f'tcp/127.0.0.1:{free_port()}'
    for key in ('ZENOH_CONFIG_OVERRIDE', 'ZENOH_SESSION_CONFIG_URI', 'ZENOH_ROUTER_CONFIG_URI'):
        os.environ.pop(key, None)
    router = zenoh.open(router_config(endpoint, env={}))
    os.environ['ROS2LITE_ROUTER'] = endpoint
    # a node pointed elsewhere must never start a daemon in the user's runtime dir
    os.environ['ROS2LITE_NO_DAEMON'] = '1'
    os.environ['ROS_DOMAIN_ID'] = str(random.randint(100, 232))
    try:
        yield endpoint
    finally:
        router.close()
        for key, value in saved.items():
            if value is None:
                os.environ.pop(key, None)
            else:
                os.environ[key] = value


@pytest.fixture
def alien_session(ros_router: str) -> Iterator[Any]:
    """A plain zenoh client session with a hand-written config: the other side of tests that
    check our wire format against the reference, not against our own code."""
    import zenoh

    conf = zenoh.Config()
    conf.insert_json5('mode', '"client"')
    conf.insert_json5('connect/endpoints', f'["{ros_router}"]')
    conf.insert_json5('scouting/multicast/enabled', 'false')
    conf.insert_json5('timestamping/enabled', 'true')  # advanced publishers need it
    session = zenoh.open(conf)
    try:
        yield session
    finally:
        session.close()


@pytest.fixture
def ros_context(ros_router: str) -> Iterator[Any]:
    """An initialised ros2lite context of this test process."""
    from ros2lite.context import Context

    ctx = Context()
    ctx.init([])
    try:
        yield ctx
    finally:
        ctx.try_shutdown()


class Processes:
    """Node processes started by a test; all are stopped (SIGINT, then SIGKILL) at teardown."""

    def __init__(self) -> None:
        self.procs: list[subprocess.Popen[str]] = []

    def python(self, code: str, *args: str, **kw: Any) -> subprocess.Popen[str]:
        return self.start([sys.executable, '-c', code, *args], **kw)

    def cli(self, *args: str, **kw: Any) -> subprocess.Popen[str]:
        return self.start([sys.executable, '-m', 'ros2lite', *args], **kw)

    def start(self, cmd: list[str], **kw: Any) -> subprocess.Popen[str]:
        kw.setdefault('stdout', subprocess.PIPE)
        kw.setdefault('stderr', subprocess.PIPE)
        proc = subprocess.Popen(cmd, text=True, **kw)
        self.procs.append(proc)
        return proc

    def stop(self, proc: subprocess.Popen[str], timeout: float = 10.0) -> tuple[str, str]:
        # a process exits within a second of SIGINT on a quiet machine; on a loaded 2-core CI
        # its interpreter teardown can take several, so SIGKILL waits longer than that
        if proc.poll() is None:
            proc.send_signal(signal.SIGINT)
        try:
            out, err = proc.communicate(timeout=timeout)
        except subprocess.TimeoutExpired:
            proc.kill()
            out, err = proc.communicate()
        return out or '', err or ''

    def close(self) -> None:
        for proc in self.procs:
            if proc.poll() is None:
                self.stop(proc, timeout=3.0)


@pytest.fixture
def processes(ros_router: str) -> Iterator[Processes]:
    procs = Processes()
    try:
        yield procs
    finally:
        procs.close()
