"""Fixtures for daemon tests: a private runtime dir, a free loopback endpoint, cleanup."""

from __future__ import annotations

import contextlib
import os
import signal
from collections.abc import Iterator
from pathlib import Path

import pytest

from tests.spinning import free_port


@pytest.fixture
def runtime(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """Point the daemon's pid/lock/log files at a temporary directory."""
    monkeypatch.setenv("XDG_RUNTIME_DIR", str(tmp_path))
    for var in (
        "ZENOH_CONFIG_OVERRIDE",
        "ZENOH_SESSION_CONFIG_URI",
        "ZENOH_ROUTER_CONFIG_URI",
        "ROS2LITE_ROUTER",
        "ROS2LITE_NO_DAEMON",
        "ZENOH_ROUTER_CHECK_ATTEMPTS",
    ):
        monkeypatch.delenv(var, raising=False)
    monkeypatch.setenv("ROS_DOMAIN_ID", "231")
    return tmp_path / "ros2lite"


@pytest.fixture
def endpoint(runtime: Path) -> Iterator[str]:
    """A free loopback endpoint; any daemon a test leaves behind on it is killed afterwards."""
    from ros2lite import daemon

    ep = f"tcp/127.0.0.1:{free_port()}"
    yield ep
    info = daemon.status(ep).info
    if info is not None:
        with contextlib.suppress(Exception):
            daemon.stop(ep, timeout=2)
        with contextlib.suppress(OSError):
            os.kill(info.pid, signal.SIGKILL)
