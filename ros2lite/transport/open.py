"""Opening what :mod:`ros2lite.transport.config` shapes: sessions and routers, and waiting for,
checking and probing the router a session needs.

Apart from the configs because opening is where zenoh's behaviour per mode shows (a client
fails in ``zenoh.open`` without its router, a peer opens anyway and hears nothing) and where
its errors become one clear line each.
"""

from __future__ import annotations

import json
import socket
import time
from collections.abc import Callable, Mapping, Sequence

import zenoh

from ros2lite.transport.config import (
    SessionMode,
    configured_endpoint,
    router_config,
    session_config,
)
from ros2lite.transport.endpoints import endpoint_host_port, router_endpoint
from ros2lite.transport.errors import RouterUnavailableError, SessionError, zerror_message
from ros2lite.transport.handles import Session
from ros2lite.transport.security import UNSECURED, Security, is_tls_endpoint
from ros2lite.transport.shm import forget, register, shm_settings

__all__ = [
    "check_router",
    "linked_routers",
    "open_router",
    "open_session",
    "router_connected",
    "router_reachable",
    "wait_for_router",
]


def open_session(
    router: str | None = None,
    *,
    mode: SessionMode = "client",
    timeout: float = 1.0,
    require_router: bool = True,
    env: Mapping[str, str] | None = None,
    security: Security = UNSECURED,
) -> zenoh.Session:
    """Open a zenoh session for ros2lite and (by default) make sure a router is really there.

    zenoh-python behaves differently per mode when the router is down: a client fails in
    ``zenoh.open`` (after ``connect/timeout_ms``), but a peer opens anyway with no router
    and just hears nothing.  So with ``require_router`` we also wait up to ``timeout``
    seconds for ``session.info.routers_zid()`` to list one, and raise
    :class:`RouterUnavailableError` (one clear line) otherwise.
    """
    config = session_config(router, env, mode=mode, security=security)
    fallback = router_endpoint(router, env, secure=security.secure_default)
    endpoint = configured_endpoint(config, fallback)
    try:
        session = zenoh.open(config)
    except zenoh.ZError as exc:
        detail = zerror_message(exc)
        if "connect" in detail.lower():
            if _handshake_refused(endpoint):
                raise SessionError(
                    f"the router at {endpoint} refused the TLS handshake (is this enclave's "
                    "certificate from the router's keystore?)"
                ) from None
            raise RouterUnavailableError(endpoint, detail) from None
        raise SessionError(f"cannot open a Zenoh session: {detail}") from None
    register(session, shm_settings(config, env))
    if not require_router:
        return session
    if not wait_for_router(session, timeout):
        forget(session)
        session.close()
        raise RouterUnavailableError(endpoint, "session opened but no router is connected")
    return session


def _handshake_refused(endpoint: str) -> bool:
    """A TLS endpoint where something accepts TCP connections, yet no session opened."""
    parsed = endpoint_host_port(endpoint)
    if not is_tls_endpoint(endpoint) or parsed is None:
        return False
    host = {"0.0.0.0": "127.0.0.1", "::": "::1"}.get(parsed[1], parsed[1])
    try:
        with socket.create_connection((host, parsed[2]), timeout=0.5):
            return True
    except OSError:
        return False


def wait_for_router(session: zenoh.Session, timeout: float) -> bool:
    """Wait up to ``timeout`` s for the session to be connected to a router."""
    deadline = time.monotonic() + timeout
    while not session.info.routers_zid():
        if time.monotonic() >= deadline:
            return False
        time.sleep(0.02)
    return True


def check_router(
    session: zenoh.Session, attempts: int, on_miss: Callable[[int], None] | None = None
) -> bool:
    """rmw_zenoh's start-up router check: ``attempts`` checks 1 s apart (0: until one answers).

    ``on_miss(n)`` is called after the n-th failed check (to log that we wait).  Returns
    whether a router is connected; a negative ``attempts`` skips the check (returns True).
    """
    if attempts < 0:
        return True
    n = 0
    while True:
        if wait_for_router(session, 1.0 if n else 0.2):
            return True
        n += 1
        if on_miss is not None:
            on_miss(n)
        if attempts and n >= attempts:
            return False


def open_router(
    endpoint: str,
    listen: Sequence[str] | None = None,
    connect: Sequence[str] = (),
    *,
    security: Security = UNSECURED,
) -> zenoh.Session:
    """A router session (the daemon's), logging zenoh's errors only; a refusal (port taken,
    bad endpoint) is a SessionError with zenoh's message in one line."""
    zenoh.init_log_from_env_or("error")
    try:
        config = router_config(endpoint, listen=listen, connect=list(connect), security=security)
        return zenoh.open(config)
    except zenoh.ZError as exc:
        raise SessionError(zerror_message(exc)) from None


def linked_routers(session: Session) -> set[str]:
    """The ids of the routers `session` is linked to now (for a router: its mesh)."""
    try:
        return {str(zid) for zid in session.info.routers_zid()}
    except zenoh.ZError:
        return set()


def router_connected(session: Session) -> bool:
    """Whether `session` is linked to a router now (a peer goes on without one)."""
    return bool(linked_routers(session))


def router_reachable(endpoint: str, timeout: float) -> bool:
    """Whether a client session to `endpoint` finds a router there (for protocols a plain
    socket connect cannot probe)."""
    config = zenoh.Config()
    config.insert_json5("mode", '"client"')
    config.insert_json5("connect/endpoints", json.dumps([endpoint]))
    config.insert_json5("connect/timeout_ms", str(max(1, int(timeout * 1000))))
    config.insert_json5("scouting/multicast/enabled", "false")
    try:
        session = zenoh.open(config)
    except zenoh.ZError:
        return False
    try:
        return bool(session.info.routers_zid())
    finally:
        session.close()
