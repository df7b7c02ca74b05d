"""The daemon process: a Zenoh router serving one endpoint until it is told to stop.

:mod:`ros2lite.daemon.control` starts, stops and inspects it; this module is what runs in
the detached process (:func:`serve`): the router, its pid file (held locked for the
process's life), the graph cache and the log lines about its mesh.
"""

from __future__ import annotations

import contextlib
import fcntl
import json
import os
import signal
import sys
import threading
import time
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, TextIO

from ros2lite.daemon.paths import graph_socket, pid_file
from ros2lite.daemon.security import refuse_plain, secured_endpoint
from ros2lite.logging import get_logger
from ros2lite.security.access import router_access
from ros2lite.security.environment import router_identity
from ros2lite.transport.open import linked_routers, open_router
from ros2lite.transport.security import Security
from ros2lite.util.files import temp_beside
from ros2lite.util.process import ignore_hangup

if TYPE_CHECKING:
    from ros2lite.daemon.graph_cache import GraphServer
    from ros2lite.transport.handles import Session

__all__ = ["DaemonInfo", "router_security", "serve"]


@dataclass(frozen=True)
class DaemonInfo:
    """What a running ros2lite daemon wrote into its pid file."""

    pid: int
    endpoint: str
    listen: list[str] = field(default_factory=list)
    connect: list[str] = field(default_factory=list)
    zid: str | None = None
    started_at: float | None = None
    log_file: str | None = None


# --------------------------------------------------------------------------- security


def router_security(env: Mapping[str, str] | None = None) -> Security:
    """The daemon router's security: its own enclave (made on first use when the CA key is
    here), and access control made from every enclave's permissions in the keystore (what
    it had to leave out goes to the log)."""
    identity = router_identity(env)
    if identity is None:
        return Security(None, refuse_plain(env))
    access = router_access(identity.keystore)
    for line in access.warnings:
        get_logger("ros2lite.security").warn(line)
    return Security(identity, refuse_plain(env), access)


# --------------------------------------------------------------------------- the process


def _write_pid_file(path: Path, info: DaemonInfo) -> TextIO:
    """Write the pid file atomically and return its handle, locked for the process' life."""
    fd, tmp = temp_beside(path)
    fh = os.fdopen(fd, "w")
    fcntl.flock(fh, fcntl.LOCK_EX)
    json.dump(info.__dict__, fh)
    fh.flush()
    os.fsync(fh.fileno())
    os.replace(tmp, path)
    return fh


def serve(
    router: str,
    listen: Sequence[str] = (),
    connect: Sequence[str] = (),
    *,
    pid_path: Path | None = None,
    log_path: Path | None = None,
    ready_fd: int | None = None,
) -> int:
    """Run the router in this process until SIGTERM/SIGINT (the body of the daemon process).

    Handshake lines go to ``ready_fd``: ``pid N`` first, then ``ready`` or ``error MSG``.
    """

    def tell(line: str) -> None:
        if ready_fd is not None:
            os.write(ready_fd, (line + "\n").encode())

    stop_signals = {signal.SIGTERM, signal.SIGINT}
    # Block before zenoh starts its threads so only our sigwait() sees these signals.
    signal.pthread_sigmask(signal.SIG_BLOCK, stop_signals)
    ignore_hangup()
    tell(f"pid {os.getpid()}")
    endpoint = secured_endpoint(router)
    try:
        session = open_router(endpoint, list(listen) or None, connect, security=router_security())
    except Exception as exc:
        msg = str(exc)
        print(f"ros2lite daemon: {msg}", file=sys.stderr, flush=True)
        tell(f"error {msg}")
        return 1
    info = DaemonInfo(
        pid=os.getpid(),
        endpoint=endpoint,
        listen=list(listen) or [endpoint],
        connect=list(connect),
        zid=str(session.zid()),
        started_at=time.time(),
        log_file=str(log_path) if log_path else None,
    )
    path = pid_path or pid_file(endpoint)
    lock = _write_pid_file(path, info)
    cache = _graph_cache(session, endpoint)
    mesh = _watch_mesh(session)
    tell("ready")
    if ready_fd is not None:
        os.close(ready_fd)
    print(f"ros2lite daemon: router {info.zid} serving {', '.join(info.listen)}", flush=True)
    try:
        sig = signal.sigwait(stop_signals)
        print(f"ros2lite daemon: {signal.Signals(sig).name}, shutting down", flush=True)
        mesh.set()
        if cache is not None:
            cache.close()
        session.close()
    finally:
        with contextlib.suppress(OSError):
            if os.stat(path).st_ino == os.fstat(lock.fileno()).st_ino:
                os.unlink(path)
        lock.close()
    return 0


def _watch_mesh(session: Session, period: float = 0.5) -> threading.Event:
    """Say in the daemon's log when a router it is meshed with (``--connect``, or one that
    connected to it) links and when that link is lost: what is published on the far side
    meanwhile does not come across, and no tool of either side would notice.  Setting the
    event returned stops the watch."""
    stop = threading.Event()

    def watch() -> None:
        linked: set[str] = set()
        while not stop.wait(period):
            now = linked_routers(session)
            for zid in sorted(now - linked):
                print(f"ros2lite daemon: linked to router {zid}", flush=True)
            for zid in sorted(linked - now):
                print(
                    f"ros2lite daemon: lost the link to router {zid}: what is published on "
                    "its side does not come across until it is back",
                    file=sys.stderr,
                    flush=True,
                )
            linked = now

    threading.Thread(target=watch, daemon=True, name="ros2lite-mesh").start()
    return stop


def _graph_cache(session: Session, endpoint: str) -> GraphServer | None:
    """Serve the graph to local tools; a daemon that cannot (say, no room for the socket)
    still routes, and tools ask the router instead."""
    from ros2lite.daemon.graph_cache import GraphServer

    try:
        return GraphServer(session, graph_socket(endpoint))
    except OSError as exc:
        print(f"ros2lite daemon: no graph cache: {exc}", file=sys.stderr, flush=True)
        return None
