"""The daemon's graph cache: every liveliness token its router knows, served to local tools.

ros2cli's daemon exists so that `ros2 topic list` need not join the graph to answer; this is
ours. The daemon keeps a liveliness subscriber (with history) on every domain and answers a
question on a Unix socket beside its pid file: a tool sends ``graph <domain>`` and reads back
the token keys of that domain, one per line, after a version line. The tool parses them as
it would the replies of a liveliness query, so a graph verb costs no zenoh import, no session
and no query — what made `topic list` slow (see :class:`ros2lite.tools.connection.Connection`).

The socket lives in the user's private runtime dir (0700), so only the user reaches it; what
it returns is parsed and validated like anything from the wire. A daemon that is not there (or
not ours: rmw_zenohd) has no socket, and tools fall back to asking the router.

The cache is bounded (:data:`LIMIT` tokens over all domains): a flood of tokens cannot grow the
daemon without end.  Tokens past the bound are dropped and counted, the daemon's log says so,
and while a domain has dropped tokens alive the cache answers that it is incomplete, so tools
ask the router for that domain instead (slower, never wrong); ``stats`` tells the counts.
"""

from __future__ import annotations

import contextlib
import errno
import os
import socket
import sys
import threading
from collections.abc import Iterator, Mapping
from pathlib import Path
from typing import TYPE_CHECKING

from ros2lite.daemon.paths import graph_socket
from ros2lite.util.files import UnsafePathError

if TYPE_CHECKING:
    from ros2lite.transport.handles import Handle, Session

__all__ = ["LIMIT", "GraphServer", "cache_endpoint", "cache_stats", "cached_keys"]

# tokens kept over all domains: a ROS graph has hundreds, a flood (R-G18) hundreds of thousands
LIMIT = 50_000
_VERSION = b"ros2lite-graph 1\n"
_INCOMPLETE = b"ros2lite-graph incomplete\n"
_REQUEST_MAX = 64  # bytes of a request line
_REPLY_MAX = 64 << 20  # what a tool reads at most (a bounded read of a local peer)
# Unix socket paths are short (108 bytes on Linux, less elsewhere); longer ones go through
# the directory's descriptor (/proc/self/fd/N/name)
_PATH_MAX = 100


@contextlib.contextmanager
def _address(path: Path) -> Iterator[str]:
    """A name for `path` that fits a socket address."""
    if len(os.fsencode(str(path))) < _PATH_MAX:
        yield str(path)
        return
    o_path = getattr(os, "O_PATH", None)  # Linux; elsewhere such a path has no cache
    if o_path is None:
        raise OSError(errno.ENAMETOOLONG, "path too long for a socket address", str(path))
    fd = os.open(path.parent, o_path | os.O_DIRECTORY | os.O_CLOEXEC)
    try:
        yield f"/proc/self/fd/{fd}/{path.name}"
    finally:
        os.close(fd)


class GraphServer:
    """The daemon's side (its router session, its socket path): started at once, in threads."""

    def __init__(self, session: Session, path: Path, limit: int = LIMIT) -> None:
        from ros2lite.transport.session import declare_liveliness_subscriber

        self._lock = threading.Lock()
        self._keys: dict[int, dict[str, None]] = {}  # by domain, in arrival order
        self.limit = limit
        self.kept = 0  # tokens in the cache
        self.dropped = 0  # tokens not kept since the start, the cache being full
        self._missing: dict[int, int] = {}  # by domain: dropped tokens still alive
        self._path = path
        self._listener = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
        with contextlib.suppress(FileNotFoundError):
            os.unlink(path)  # a dead daemon's socket (the runtime dir is ours alone)
        with _address(path) as address:
            self._listener.bind(address)
        os.chmod(path, 0o600)
        self._inode = os.stat(path).st_ino
        self._listener.listen(16)
        self._sub: Handle = declare_liveliness_subscriber(session, None, self._on_change)
        self._thread = threading.Thread(target=self._serve, daemon=True, name="ros2lite-graph")
        self._thread.start()

    def _on_change(self, key: str, alive: bool) -> None:
        if "\n" in key:
            # served one key a line: a newline in a key would forge a second token, so such a
            # key is kept escaped, as a line no tool takes for a token (and reports as skipped)
            key = "#" + key.encode("unicode_escape").decode("ascii")
        domain = key.split("/", 2)[1] if key.count("/") >= 2 else ""
        if not (domain.isascii() and domain.isdigit()):  # ('²' is a digit int() refuses)
            return  # not a token rmw_zenoh would make: tools would drop it anyway
        number = int(domain)
        with self._lock:
            keys = self._keys.setdefault(number, {})
            if not alive:
                if key in keys:
                    del keys[key]
                    self.kept -= 1
                elif self._missing.get(number):
                    self._missing[number] -= 1
                return
            if key in keys:
                return
            if self.kept < self.limit:
                keys[key] = None
                self.kept += 1
                return
            self._missing[number] = self._missing.get(number, 0) + 1
            self.dropped += 1
            dropped = self.dropped
        if dropped & (dropped - 1) == 0:  # the first drop, then at every power of two
            print(
                f"ros2lite daemon: graph cache full ({self.limit} tokens): {dropped} token(s) "
                f"not kept so far (last in domain {number}); tools ask the router for a "
                "domain while any of its dropped tokens lives",
                file=sys.stderr,
                flush=True,
            )

    def keys(self, domain: int) -> list[str] | None:
        """The token keys of a domain now; None while some are missing (dropped)."""
        with self._lock:
            if self._missing.get(domain):
                return None
            return list(self._keys.get(domain, ()))

    def _serve(self) -> None:
        while True:
            try:
                conn, _ = self._listener.accept()
            except OSError:
                return  # closed
            with conn, contextlib.suppress(OSError):
                conn.settimeout(1.0)  # a tool that connects and says nothing holds no one up
                self._answer(conn)

    def _answer(self, conn: socket.socket) -> None:
        request = b""
        while not request.endswith(b"\n") and len(request) < _REQUEST_MAX:
            chunk = conn.recv(_REQUEST_MAX)
            if not chunk:
                return
            request += chunk
        verb, _, domain = request.decode("ascii", "replace").strip().partition(" ")
        if verb == "stats" and not domain:
            with self._lock:
                counts = f"kept {self.kept}\ndropped {self.dropped}\nlimit {self.limit}"
            conn.sendall(_VERSION + counts.encode())
            return
        if verb != "graph" or not (domain.isascii() and domain.isdigit()):
            return
        keys = self.keys(int(domain))
        conn.sendall(_INCOMPLETE if keys is None else _VERSION + "\n".join(keys).encode())

    def close(self) -> None:
        """Stop serving; the socket file goes."""
        from ros2lite.transport.session import undeclare_quietly

        undeclare_quietly(self._sub)
        with contextlib.suppress(OSError):
            self._listener.shutdown(socket.SHUT_RDWR)  # wakes the accept()
        self._listener.close()
        self._thread.join(timeout=1.0)
        with contextlib.suppress(OSError):
            if os.stat(self._path).st_ino == self._inode:
                os.unlink(self._path)


def cache_endpoint(router: str | None = None, env: Mapping[str, str] | None = None) -> str | None:
    """The endpoint whose daemon may answer graph questions, None when its cache would not
    see what this process' session would: a session the user configured
    (``ZENOH_SESSION_CONFIG_URI``/``ZENOH_CONFIG_OVERRIDE``) or a secured graph."""
    from ros2lite.security.environment import security_enabled
    from ros2lite.transport.endpoints import OVERRIDE_ENV, SESSION_CONFIG_ENV, environ
    from ros2lite.transport.endpoints import router_endpoint as endpoint_of

    values = environ(env)
    if values.get(SESSION_CONFIG_ENV) or values.get(OVERRIDE_ENV) or security_enabled(env):
        return None
    return endpoint_of(router, env)


def _ask(endpoint: str, request: str, timeout: float) -> str | None:
    """The daemon's answer to one request line (after the version line), None when no
    daemon of ours answers it (or this user has no safe place for a daemon's files: no
    usable home, say)."""
    try:
        path = graph_socket(endpoint)
    except UnsafePathError:
        return None
    chunks: list[bytes] = []
    with socket.socket(socket.AF_UNIX, socket.SOCK_STREAM) as sock:
        sock.settimeout(timeout)
        try:
            with _address(path) as address:
                sock.connect(address)
            sock.sendall(f"{request}\n".encode())
            size = 0
            while size <= _REPLY_MAX:
                chunk = sock.recv(1 << 16)
                if not chunk:
                    break
                chunks.append(chunk)
                size += len(chunk)
            else:
                return None  # more than any graph: not our daemon talking
        except OSError:  # none, a stale socket, refused, timed out, no address for it
            return None
    reply = b"".join(chunks)
    if not reply.startswith(_VERSION):
        return None  # not ours, or a domain the cache could not keep whole
    return reply[len(_VERSION) :].decode("utf-8", "replace")


def cached_keys(endpoint: str, domain: int, timeout: float = 1.0) -> list[str] | None:
    """The token keys of `domain` from the daemon at `endpoint`, None when none answers
    (or its cache, full, lacks some of that domain's)."""
    body = _ask(endpoint, f"graph {domain}", timeout)
    if body is None:
        return None
    return body.split("\n") if body else []


def cache_stats(endpoint: str, timeout: float = 1.0) -> dict[str, int] | None:
    """The daemon cache's counts (``kept``, ``dropped``, ``limit``), None without one."""
    body = _ask(endpoint, "stats", timeout)
    if body is None:
        return None
    stats: dict[str, int] = {}
    for line in body.split("\n"):
        name, _, value = line.partition(" ")
        if name in ("kept", "dropped", "limit") and value.isascii() and value.isdigit():
            stats[name] = int(value)
    return stats
