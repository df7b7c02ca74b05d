from __future__ import annotations

import json
import os
import socket
import subprocess
import sys
import threading
import time
from pathlib import Path

import pytest
import zenoh

from ros2lite import daemon
from ros2lite.daemon.errors import DaemonError
from ros2lite.daemon.paths import pid_file
from ros2lite.transport.config import router_config
from ros2lite.transport.open import open_session

from .conftest import free_port


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    stat = Path(f"/proc/{pid}/stat")
    return not (stat.exists() and stat.read_text().split()[2] == "Z")


def test_start_status_pubsub_stop(endpoint: str, runtime: Path) -> None:
    assert not daemon.status(endpoint).running

    result = daemon.start(endpoint)
    assert result.started and result.ours and not result.already_running
    assert result.pid and _alive(result.pid)
    assert result.message == "The daemon has been started"

    st = daemon.status(endpoint)
    assert st.running and st.ours and st.pid == result.pid
    assert st.info is not None and st.info.listen == [endpoint] and st.info.zid
    assert st.message == "The daemon is running"
    assert pid_file(endpoint).parent == runtime

    again = daemon.start(endpoint)
    assert not again.started and again.already_running and again.ours
    assert again.message == "The daemon is already running"

    # The router really routes: two client sessions talk through it.
    a, b = open_session(endpoint), open_session(endpoint)
    try:
        assert [str(z) for z in a.info.routers_zid()] == [st.info.zid]
        got = threading.Event()
        sub = b.declare_subscriber("231/chatter/x/y", lambda s: got.set())
        deadline = time.monotonic() + 5
        while not got.is_set() and time.monotonic() < deadline:
            a.put("231/chatter/x/y", b"hi")
            got.wait(0.05)
        assert got.is_set()
        sub.undeclare()
    finally:
        a.close()
        b.close()

    stopped = daemon.stop(endpoint)
    assert stopped.stopped and stopped.pid == result.pid
    assert stopped.message == "The daemon has been stopped"
    assert not _alive(result.pid)
    assert not daemon.status(endpoint).running
    assert not pid_file(endpoint).exists()
    assert daemon.stop(endpoint).message == "The daemon is not running"
    assert "SIGTERM" in Path(result.log_file or "").read_text()


def test_stale_pid_file_is_cleaned(endpoint: str, runtime: Path) -> None:
    dead = subprocess.Popen([sys.executable, "-c", "pass"])
    dead.wait()
    path = pid_file(endpoint)
    path.write_text(json.dumps({"pid": dead.pid, "endpoint": endpoint}))
    st = daemon.status(endpoint)
    assert not st.running and not st.ours
    assert not path.exists()
    path.write_text(json.dumps({"pid": dead.pid, "endpoint": endpoint}))
    assert daemon.stop(endpoint).message == "The daemon is not running"
    assert not path.exists()


def test_killed_daemon_leaves_stale_file_that_start_replaces(endpoint: str) -> None:
    first = daemon.start(endpoint)
    assert first.pid
    os.kill(first.pid, 9)
    deadline = time.monotonic() + 5
    while daemon.status(endpoint).running and time.monotonic() < deadline:
        time.sleep(0.05)
    second = daemon.start(endpoint)
    assert second.started and second.pid != first.pid
    assert daemon.stop(endpoint).stopped


def test_foreign_router_is_used_not_stopped(endpoint: str) -> None:
    foreign = zenoh.open(router_config(endpoint, env={}))
    try:
        st = daemon.status(endpoint)
        assert st.running and not st.ours
        result = daemon.start(endpoint)
        assert result.already_running and not result.started and not result.ours
        assert "not started by ros2lite" in result.message
        stop = daemon.stop(endpoint)
        assert not stop.stopped and stop.foreign
        assert daemon.router_answers(endpoint)
        assert daemon.ensure_running(endpoint).already_running
    finally:
        foreign.close()


def test_ensure_running_starts_once(endpoint: str) -> None:
    first = daemon.ensure_running(endpoint)
    assert first.started
    second = daemon.ensure_running(endpoint)
    assert second.already_running and second.ours and second.pid == first.pid
    assert daemon.stop(endpoint).stopped


def test_start_failure_is_reported(endpoint: str) -> None:
    with socket.socket() as busy:
        busy.bind(("127.0.0.1", 0))
        busy.listen()
        port = busy.getsockname()[1]
        start = time.monotonic()
        with pytest.raises(DaemonError, match="Address already in use"):
            daemon.start(endpoint, listen=[f"tcp/127.0.0.1:{port}"])
        assert time.monotonic() - start < 5
    assert not pid_file(endpoint).exists()
    assert not daemon.status(endpoint).ours


def test_two_daemons_on_different_ports(endpoint: str) -> None:
    other = f"tcp/127.0.0.1:{free_port()}"
    try:
        assert daemon.start(endpoint).started
        assert daemon.start(other).started
        assert pid_file(endpoint) != pid_file(other)
        assert daemon.status(endpoint).pid != daemon.status(other).pid
        assert daemon.stop(other).stopped
        assert daemon.status(endpoint).running
    finally:
        daemon.stop(other)
        daemon.stop(endpoint)


def test_router_answers_probe() -> None:
    with socket.socket() as listener:
        listener.bind(("127.0.0.1", 0))
        listener.listen()
        port = listener.getsockname()[1]
        assert daemon.router_answers(f"tcp/127.0.0.1:{port}")
    start = time.monotonic()
    assert not daemon.router_answers(f"tcp/127.0.0.1:{free_port()}")
    assert time.monotonic() - start < 0.5


def test_config_override_reaches_the_daemon(endpoint: str, monkeypatch: pytest.MonkeyPatch) -> None:
    # The router's admin space is off by default; the override turns it on in the daemon.
    monkeypatch.setenv("ZENOH_CONFIG_OVERRIDE", "adminspace/enabled=true")
    assert daemon.start(endpoint).started
    zid = daemon.status(endpoint).info.zid  # type: ignore[union-attr]
    session = open_session(endpoint)
    try:
        replies = list(session.get(f"@/{zid}/router", zenoh.handlers.FifoChannel(16), timeout=2))
        assert [str(r.ok.key_expr) for r in replies if r.ok] == [f"@/{zid}/router"]
        assert endpoint in replies[0].ok.payload.to_string()  # type: ignore[union-attr]
    finally:
        session.close()
        daemon.stop(endpoint)
