"""Start, stop and inspect the ros2lite daemon: a Zenoh router in a detached process
(:mod:`ros2lite.daemon.router` is what runs there).

Bookkeeping lives in the user's runtime dir (``$XDG_RUNTIME_DIR/ros2lite``, else
``~/.cache/ros2lite``), one set of files per router endpoint so daemons on different ports
coexist: ``router-<endpoint>.pid`` (JSON), ``.log`` and ``.lock``.

Liveness is decided by an ``flock`` that the daemon holds on its pid file for its whole
life, not by ``kill(pid, 0)``: the kernel drops the lock when the process dies (even on
SIGKILL), so a recycled pid can never make a stale file look alive, and a dead daemon is
detected without waiting for anyone to reap it.
"""

from __future__ import annotations

import contextlib
import fcntl
import json
import os
import signal
import site
import subprocess
import sys
import time
from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

from ros2lite.daemon.errors import DaemonError
from ros2lite.daemon.paths import lock_file, log_file, pid_file
from ros2lite.daemon.probe import (
    not_a_router,
    router_answers,
    secured_router,
    speaks_tls,
    speaks_zenoh,
    wait_answers,
)
from ros2lite.daemon.router import DaemonInfo, router_security
from ros2lite.daemon.security import secured_endpoint, session_security
from ros2lite.security.errors import SecurityError
from ros2lite.transport.config import domain_id, router_config
from ros2lite.transport.errors import SessionError
from ros2lite.transport.open import open_session
from ros2lite.util.files import NOFOLLOW

if TYPE_CHECKING:
    from ros2lite.transport.admin import ConnectedSession
    from ros2lite.transport.security import Security

__all__ = [
    "DaemonStatus",
    "StartResult",
    "StopResult",
    "connected_sessions",
    "daemon_pid",
    "ensure_running",
    "start",
    "status",
    "stop",
]


START_TIMEOUT = 10.0
STOP_TIMEOUT = 5.0
_CMDLINE_MARK = b"ros2lite.daemon"


@dataclass(frozen=True)
class StartResult:
    """What `daemon start` found or did at an endpoint."""

    endpoint: str
    started: bool  # True when this call spawned the router
    already_running: bool  # something already answered at the endpoint
    ours: bool  # the router serving the endpoint is a ros2lite daemon
    pid: int | None = None
    log_file: str | None = None

    @property
    def message(self) -> str:
        """The line `daemon start` prints."""
        if self.started:
            return "The daemon has been started"
        if self.ours:
            return "The daemon is already running"
        return (
            "The daemon is already running (a Zenoh router not started by ros2lite "
            f"answers at {self.endpoint})"
        )


@dataclass(frozen=True)
class StopResult:
    """What `daemon stop` found or did at an endpoint."""

    endpoint: str
    stopped: bool
    foreign: bool = False  # a router answers there, but it is not ours to stop
    pid: int | None = None
    # the sessions that were connected when it was stopped (None: unknown)
    sessions: list[ConnectedSession] | None = None

    @property
    def message(self) -> str:
        """The line `daemon stop` prints."""
        if self.stopped:
            return "The daemon has been stopped"
        if self.foreign:
            return f"The router at {self.endpoint} was not started by ros2lite; not stopping it"
        return "The daemon is not running"


@dataclass(frozen=True)
class DaemonStatus:
    """What `daemon status` found at an endpoint."""

    endpoint: str
    running: bool  # something answers at the endpoint
    ours: bool  # a live ros2lite daemon owns the endpoint
    info: DaemonInfo | None = None
    # other sessions connected to the router, when asked for and its admin space answers
    sessions: list[ConnectedSession] | None = None
    answers_zenoh: bool = True  # False: something listens, but no Zenoh router answers
    # it speaks TLS (the endpoint is tls/, or a TLS listener sits behind a tcp/ one)
    secured: bool = False
    has_enclave: bool = False  # this process has a certificate to offer a secured router

    @property
    def pid(self) -> int | None:
        """The daemon's process id, when it is ours."""
        return self.info.pid if self.info else None

    @property
    def message(self) -> str:
        """The line `daemon status` prints."""
        if self.running and not self.answers_zenoh:
            if self.secured:  # there, and secured: not frozen
                return secured_router(self.endpoint, self.pid, has_enclave=self.has_enclave)
            return not_a_router(self.endpoint, self.pid)
        if self.running and self.ours:
            return "The daemon is running"
        if self.running:
            return (
                f"The daemon is running (a Zenoh router not started by ros2lite at {self.endpoint})"
            )
        if self.ours:
            return (
                f"The daemon process (pid {self.pid}) exists but does not answer at {self.endpoint}"
            )
        return "The daemon is not running"


# --------------------------------------------------------------------------- files


@contextlib.contextmanager
def _start_lock(endpoint: str, timeout: float) -> Iterator[None]:
    """Serialise start/stop for one endpoint so two auto-starting CLIs don't race."""
    fd = os.open(lock_file(endpoint), os.O_RDWR | os.O_CREAT | NOFOLLOW | os.O_CLOEXEC, 0o600)
    with os.fdopen(fd, "r+") as fh:
        deadline = time.monotonic() + timeout
        while True:
            try:
                fcntl.flock(fh, fcntl.LOCK_EX | fcntl.LOCK_NB)
                break
            except BlockingIOError:
                if time.monotonic() > deadline:
                    raise DaemonError(
                        f"another ros2lite process is starting/stopping the daemon for {endpoint}"
                    ) from None
                time.sleep(0.05)
        try:
            yield
        finally:
            fcntl.flock(fh, fcntl.LOCK_UN)


def _read_info(path: Path) -> DaemonInfo | None:
    """The pid file's content if a live daemon holds it; stale files are removed."""
    try:
        fh = open(path)  # noqa: SIM115 - closed by the 'with' below
    except FileNotFoundError:
        return None
    with fh:
        try:
            fcntl.flock(fh, fcntl.LOCK_SH | fcntl.LOCK_NB)
        except BlockingIOError:
            try:
                data: dict[str, Any] = json.loads(fh.read() or "{}")  # JSON: checked below
                return DaemonInfo(
                    pid=int(data["pid"]),
                    endpoint=str(data["endpoint"]),
                    listen=list(data.get("listen", [])),
                    connect=list(data.get("connect", [])),
                    zid=data.get("zid"),
                    started_at=data.get("started_at"),
                    log_file=data.get("log_file"),
                )
            except (ValueError, KeyError, TypeError):
                return None  # held but unreadable: being written; treat as unknown
        # We got the lock, so nobody holds it: the daemon is gone.  Remove the file only
        # if the path still names the inode we locked (a new daemon may have replaced it).
        try:
            if os.stat(path).st_ino == os.fstat(fh.fileno()).st_ino:
                os.unlink(path)
        except FileNotFoundError:
            pass
        return None


def _is_our_process(pid: int) -> bool:
    """Double-check a pid really runs ``ros2lite.daemon`` (where /proc exists)."""
    cmdline = Path(f"/proc/{pid}/cmdline")
    if not Path("/proc/self/cmdline").exists():
        return True
    try:
        return _CMDLINE_MARK in cmdline.read_bytes()
    except OSError:
        return False


# --------------------------------------------------------------------------- verbs


def daemon_pid(router: str | None = None) -> int | None:
    """The pid of our live daemon for the endpoint, if there is one (reads its pid file)."""
    try:
        info = _read_info(pid_file(secured_endpoint(router)))
    except OSError:
        return None
    return info.pid if info is not None else None


def status(router: str | None = None, *, sessions: bool = False) -> DaemonStatus:
    """Is a router answering at the endpoint, and is it ours?  With ``sessions``, also
    which sessions are connected to it (one short client session asks its admin space).
    A listener that does not answer as a Zenoh router is told apart (``answers_zenoh``)."""
    endpoint = secured_endpoint(router)
    info = _read_info(pid_file(endpoint))
    running = router_answers(endpoint)
    security = _security_or_none()
    zenoh = not running or _answers_zenoh(endpoint, security)
    connected = connected_sessions(endpoint) if running and zenoh and sessions else None
    secured = running and (endpoint.startswith("tls/") or (not zenoh and speaks_tls(endpoint)))
    enclave = security is not None and security.credentials is not None
    return DaemonStatus(
        endpoint, running, info is not None, info, connected, zenoh, secured, enclave
    )


def _security_or_none() -> Security | None:
    """This process's session security; None when it cannot have any (Enforce without
    material: the probe then goes without, and says what it sees)."""
    try:
        return session_security()
    except SecurityError:
        return None


def _answers_zenoh(endpoint: str, security: Security | None) -> bool:
    """Does a Zenoh router answer at `endpoint`? A tls/ one is asked with this process's
    certificate (a session without one is refused: that is not a frozen router)."""
    if endpoint.startswith("tls/") and security is not None and security.credentials is not None:
        try:
            session = open_session(endpoint, mode="client", timeout=1.0, security=security)
        except (SessionError, SecurityError):
            return False
        session.close()
        return True
    return speaks_zenoh(endpoint)


def connected_sessions(
    router: str | None = None, timeout: float = 2.0
) -> list[ConnectedSession] | None:
    """The sessions linked to the router at the endpoint, with their node names; None when
    no router answers or its admin space is closed (e.g. a foreign router's)."""
    from ros2lite.transport.admin import router_sessions

    try:
        security = session_security()
        endpoint = secured_endpoint(router)
        session = open_session(endpoint, mode="client", timeout=timeout, security=security)
    except (SessionError, SecurityError):  # e.g. no enclave of our own on a secured graph
        return None
    try:
        return router_sessions(session, domain_id(), timeout)
    finally:
        session.close()


def start(
    router: str | None = None,
    listen: Sequence[str] = (),
    connect: Sequence[str] = (),
    *,
    timeout: float = START_TIMEOUT,
    known_absent: bool = False,
) -> StartResult:
    """Spawn a detached router for the endpoint unless something already answers there.

    ``listen`` defaults to the endpoint itself (loopback-only for the default endpoint);
    pass e.g. ``tcp/0.0.0.0:7447`` to open it to the network.  ``connect`` lists other
    routers to mesh with.  Waits up to ``timeout`` s for the router to answer.
    ``known_absent``: the caller has just probed the endpoint and nothing answered, so only
    a daemon that another process started meanwhile (its pid file) is waited for.
    """
    endpoint = secured_endpoint(router)
    # Validate config and env up front so mistakes surface here, not in a log file.
    security = router_security()
    router_config(endpoint, listen=list(listen) or None, connect=list(connect), security=security)
    with _start_lock(endpoint, timeout):
        info = _read_info(pid_file(endpoint))
        if (not known_absent and router_answers(endpoint)) or (
            info is not None and wait_answers(endpoint, timeout)
        ):
            pid = info.pid if info else None
            mine = _security_or_none()
            if not _answers_zenoh(endpoint, mine):
                if speaks_tls(endpoint):  # secured, and this process cannot get in
                    has = mine is not None and mine.credentials is not None
                    raise DaemonError(secured_router(endpoint, pid, has_enclave=has))
                raise DaemonError(not_a_router(endpoint, pid))  # frozen, or not a router
            return StartResult(
                endpoint,
                False,
                True,
                info is not None,
                info.pid if info else None,
                info.log_file if info else None,
            )
        if info is not None:
            raise DaemonError(
                f"ros2lite daemon pid {info.pid} runs but does not answer at {endpoint}; "
                f"see {info.log_file} or run 'ros2lite daemon stop'"
            )
        pid = _spawn(endpoint, list(listen), list(connect), timeout)
        return StartResult(endpoint, True, False, True, pid, str(log_file(endpoint)))


def _spawn(endpoint: str, listen: list[str], connect: list[str], timeout: float) -> int:
    log = log_file(endpoint)
    cmd = [
        sys.executable,
        "-m",
        "ros2lite.daemon",
        "--router",
        endpoint,
        "--pid-file",
        str(pid_file(endpoint)),
        "--log-file",
        str(log),
    ]
    for ep in listen:
        cmd += ["--listen", ep]
    for ep in connect:
        cmd += ["--connect", ep]
    env = dict(os.environ)
    # The daemon runs from '/', so relative config paths and an uninstalled source tree
    # must be made absolute here.
    for var in ("ZENOH_ROUTER_CONFIG_URI", "ZENOH_SESSION_CONFIG_URI"):
        if env.get(var):
            env[var] = os.path.abspath(env[var])
    src_root = str(Path(__file__).resolve().parents[2])
    if src_root not in _site_dirs():
        env["PYTHONPATH"] = os.pathsep.join(p for p in (src_root, env.get("PYTHONPATH")) if p)
    proc = subprocess.Popen(
        cmd,
        stdin=subprocess.DEVNULL,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        cwd="/",
        env=env,
        close_fds=True,
        text=True,
    )
    try:
        out, err = proc.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        proc.kill()
        out, err = proc.communicate()
        _kill_pid_from(out)
        raise DaemonError(
            f"the router did not come up at {endpoint} within {timeout:.0f} s; see {log}"
        ) from None
    lines = out.splitlines()
    if proc.returncode != 0 or "ready" not in lines:
        _kill_pid_from(out)
        why = next((ln[6:] for ln in lines if ln.startswith("error ")), "") or err.strip()
        raise DaemonError(
            f"could not start a router at {endpoint}: {why or 'unknown error'} (log: {log})"
        )
    pid = _pid_from(out) or 0
    if not wait_answers(endpoint, timeout):
        raise DaemonError(
            f"the router (pid {pid}) started but does not answer at {endpoint}; "
            f"check --listen (log: {log})"
        )
    return pid


def _site_dirs() -> set[str]:
    """Directories a fresh interpreter finds packages in anyway (never put them first)."""
    dirs = set(site.getsitepackages()) if hasattr(site, "getsitepackages") else set()
    dirs.add(site.getusersitepackages())
    return {str(Path(d).resolve()) for d in dirs}


def _pid_from(handshake: str) -> int | None:
    for line in handshake.splitlines():
        if line.startswith("pid "):
            with contextlib.suppress(ValueError):
                return int(line[4:])
    return None


def _kill_pid_from(handshake: str) -> None:
    pid = _pid_from(handshake)
    if pid:
        with contextlib.suppress(OSError):
            os.kill(pid, signal.SIGKILL)


def _pid_gone(pid: int) -> bool:
    """True when ``pid`` has exited (a zombie nobody reaped yet counts as exited)."""
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return True
    except PermissionError:
        return False
    try:
        return Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0] == "Z"
    except (OSError, IndexError):
        return False


def _exited(path: Path, pid: int) -> bool:
    info = _read_info(path)
    return (info is None or info.pid != pid) and _pid_gone(pid)


def stop(router: str | None = None, *, timeout: float = STOP_TIMEOUT) -> StopResult:
    """Stop our own daemon for the endpoint (never a foreign router); clean stale files."""
    endpoint = secured_endpoint(router)
    path = pid_file(endpoint)
    with _start_lock(endpoint, timeout + 1):
        info = _read_info(path)
        if info is None or not _is_our_process(info.pid):
            return StopResult(endpoint, False, foreign=router_answers(endpoint))
        # asked before stopping, so `daemon stop` can say who is cut off
        sessions = connected_sessions(endpoint) if router_answers(endpoint) else None
        for sig, wait in ((signal.SIGTERM, timeout), (signal.SIGKILL, 2.0)):
            try:
                os.kill(info.pid, sig)
            except ProcessLookupError:
                break
            deadline = time.monotonic() + wait
            while time.monotonic() < deadline:
                with contextlib.suppress(ChildProcessError, OSError):
                    os.waitpid(info.pid, os.WNOHANG)  # reaps only if it is our child
                if _exited(path, info.pid):
                    break
                time.sleep(0.05)
            if _exited(path, info.pid):
                break
        else:
            raise DaemonError(f"daemon pid {info.pid} did not exit")
        _read_info(path)  # removes the file if the daemon died without cleaning up
        return StopResult(endpoint, True, pid=info.pid, sessions=sessions)


def ensure_running(router: str | None = None, *, timeout: float = START_TIMEOUT) -> StartResult:
    """Make sure a router answers, starting our daemon if none does (what `start` does when
    something already answers: it says so and starts nothing)."""
    return start(router, timeout=timeout)
