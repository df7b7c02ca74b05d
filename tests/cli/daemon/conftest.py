"""A private router endpoint and runtime dir per test; any daemon left behind is stopped."""

from __future__ import annotations

import contextlib
import os
import signal
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

import pytest

from tests.conftest import free_port


@dataclass
class Private:
    endpoint: str
    runtime: Path
    env: dict[str, str]  # extra environment for run_process


@pytest.fixture
def private(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Iterator[Private]:
    endpoint = f'tcp/127.0.0.1:{free_port()}'
    runtime = tmp_path / 'run'
    runtime.mkdir()
    # this process too, so the daemon library below looks at the same pid files
    monkeypatch.setenv('XDG_RUNTIME_DIR', str(runtime))
    monkeypatch.setenv('ROS2LITE_ROUTER', endpoint)
    for var in ('ZENOH_CONFIG_OVERRIDE', 'ZENOH_SESSION_CONFIG_URI', 'ZENOH_ROUTER_CONFIG_URI'):
        monkeypatch.delenv(var, raising=False)
    yield Private(endpoint, runtime, {'XDG_RUNTIME_DIR': str(runtime), 'ROS2LITE_ROUTER': endpoint})
    from ros2lite import daemon

    info = daemon.status(endpoint).info
    if info is not None:
        with contextlib.suppress(Exception):
            daemon.stop(endpoint, timeout=2)
        with contextlib.suppress(OSError):
            os.kill(info.pid, signal.SIGKILL)
