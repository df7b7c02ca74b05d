"""The one way ros2lite opens a session: :func:`connect`, for nodes and for tools.

Tools (CLI verbs, completion, scripts inspecting the graph) open a *client* session: one cheap
probe of the router endpoint, the daemon started when nothing answers (unless told not to),
then one link that fails fast with :class:`RouterUnavailableError` when no router is there.

A node is started from a tutorial, a launch file or a service manager, often before any CLI
verb has started the daemon, so a missing router must not be fatal.  In order:

1. If no router answers at the node's router endpoint, that endpoint is on this host and the
   user did not opt out, start the ros2lite daemon there, as the CLI's graph verbs do.
   Opting out: ``ROS2LITE_NO_DAEMON=1``, or setting ``ZENOH_ROUTER_CHECK_ATTEMPTS`` (whoever
   sets it manages the router, as with rmw_zenoh).  Nothing is started for an endpoint that
   ``ZENOH_SESSION_CONFIG_URI``/``ZENOH_CONFIG_OVERRIDE`` replaced: that router is the user's.
2. Open the session in the node mode (peer, see :mod:`ros2lite.transport.config`).
3. If still no router is connected, do rmw_zenoh's check (``ZENOH_ROUTER_CHECK_ATTEMPTS``:
   unset 1 check, N checks 1 s apart, 0 until one answers, negative none), log one line and
   carry on: the peer keeps retrying and joins the graph as soon as a router runs.

A session forced into client mode (a remote router, or ``mode="client"`` in an override)
cannot open without its router and fails with :class:`RouterUnavailableError` instead.

Security comes from :mod:`ros2lite.daemon.security`, decided once per session.
"""

from __future__ import annotations

import os
from collections.abc import Mapping
from typing import TYPE_CHECKING

from ros2lite.daemon.security import session_security
from ros2lite.transport.config import (
    CONNECT_TIMEOUT_MS,
    configured_mode,
    node_session_mode,
    session_config,
    session_endpoint,
)
from ros2lite.transport.endpoints import (
    ROUTER_CHECK_ENV,
    default_router,
    is_local_endpoint,
    router_check_attempts,
    router_endpoint,
)
from ros2lite.transport.errors import RouterUnavailableError
from ros2lite.transport.open import check_router, open_session
from ros2lite.transport.security import Security

if TYPE_CHECKING:
    from ros2lite.transport.handles import Session

__all__ = [
    "NO_DAEMON_ENV",
    "autostart_enabled",
    "connect",
    "node_is_client",
    "open_node_session",
    "started_elsewhere",
]

NO_DAEMON_ENV = "ROS2LITE_NO_DAEMON"
LOGGER_NAME = "ros2lite"


def _truthy(value: str) -> bool:
    return value.strip().lower() not in ("", "0", "false", "no", "off")


def autostart_enabled(env: Mapping[str, str] | None = None) -> bool:
    """May a node start the daemon?  Not with ``ROS2LITE_NO_DAEMON`` set or when the user
    manages the router the rmw_zenoh way (``ZENOH_ROUTER_CHECK_ATTEMPTS`` set)."""
    environ = os.environ if env is None else env
    return (
        not _truthy(environ.get(NO_DAEMON_ENV, ""))
        and not environ.get(ROUTER_CHECK_ENV, "").strip()
    )


def _log(severity: str, message: str) -> None:
    from ros2lite.logging import get_logger

    logger = get_logger(LOGGER_NAME)
    (logger.warn if severity == "warn" else logger.info)(message)


def started_elsewhere(
    endpoint: str, pid: int | None, *, secure: bool = False, default: str | None = None
) -> str | None:
    """The line said when the daemon was just started at an endpoint the user named
    (``--router``, ``ROS2LITE_ROUTER``) rather than the default one (`default`: the default
    endpoint, for tests): a mistyped endpoint would otherwise make a second, empty graph in
    silence. It adds that a router answers at the default endpoint when one does (the likely
    typo). None at the default endpoint, where starting it is the quick start's promise."""
    from ros2lite.daemon.probe import router_answers

    usual = default or default_router(secure)
    if endpoint == usual:
        return None
    line = (
        f"no Zenoh router answered at {endpoint}: started the ros2lite daemon there (pid "
        f"{pid}), a graph of its own at the endpoint --router or ROS2LITE_ROUTER named"
    )
    if router_answers(usual, timeout=0.2):
        line += f"; a router answers at {usual}: is the endpoint mistyped?"
    return line + f" ('ros2lite --router {endpoint} daemon stop' ends it)"


def _autostart(router: str | None, security: Security) -> None:
    """Start our daemon at the node's endpoint when nothing answers there (see module doc)."""
    from ros2lite.daemon.probe import router_answers

    endpoint = router_endpoint(router, secure=security.secure_default)
    if (
        session_endpoint(router, security=security) != endpoint
        or not is_local_endpoint(endpoint)
        or router_answers(endpoint)
    ):
        return
    from ros2lite.daemon.control import start
    from ros2lite.daemon.errors import DaemonError

    try:
        result = start(endpoint, known_absent=True)
    except DaemonError as exc:
        _log("warn", f"could not start the ros2lite daemon: {exc}")
        return
    if result.started:
        named = started_elsewhere(endpoint, result.pid, secure=security.secure_default)
        if named is not None:
            _log("warn", named)
            return
        _log(
            "info",
            f"no Zenoh router answered at {endpoint}: started the ros2lite daemon "
            f"(pid {result.pid}); set {NO_DAEMON_ENV}=1 to stop nodes doing this",
        )


def node_is_client(router: str | None = None) -> tuple[bool, str]:
    """Whether a node's session is a Zenoh client (secured, or a remote router, or so
    configured), and its router endpoint: a client hears and reaches nothing while its
    router is away, where a peer keeps the links it has."""
    security = session_security()
    mode = node_session_mode(router, security=security)
    config = session_config(router, mode=mode, security=security)
    return configured_mode(config) != "peer", session_endpoint(router, security=security)


def open_node_session(router: str | None = None) -> Session:
    """The session of a long-lived node (module doc); raises ConfigError/SessionError."""
    security = session_security()
    if autostart_enabled():
        _autostart(router, security)
    mode = node_session_mode(router, security=security)
    attempts = router_check_attempts()
    if configured_mode(session_config(router, mode=mode, security=security)) != "peer":
        return open_session(router, mode=mode, security=security)
    session = open_session(router, mode=mode, require_router=False, security=security)
    endpoint = session_endpoint(router, security=security)

    def waiting(n: int) -> None:
        if n == 1 and attempts != 1:
            more = "until one does" if attempts == 0 else f"for up to {attempts} s"
            _log(
                "warn",
                f"no Zenoh router answers at {endpoint}; waiting {more} "
                "(start one with 'ros2lite daemon start')",
            )

    try:
        found = check_router(session, attempts, waiting)
    except BaseException:  # Ctrl-C while waiting: no zenoh session may outlive the interpreter
        session.close()
        raise
    if not found:
        _log(
            "warn",
            f"no Zenoh router answers at {endpoint}: running without one; this node "
            "joins the graph as soon as a router runs ('ros2lite daemon start')",
        )
    return session


def connect(
    router: str | None = None,
    *,
    tool: bool = False,
    autostart: bool = True,
    timeout: float = CONNECT_TIMEOUT_MS / 1000,
) -> Session:
    """Open this process' session: a node's (peer, module doc) or, with `tool`, a client's.

    A tool probes the router endpoint once: when nothing answers it starts the daemon there
    (`autostart`) or fails at once with RouterUnavailableError; an endpoint that
    ``ZENOH_SESSION_CONFIG_URI``/``ZENOH_CONFIG_OVERRIDE`` replaced is the user's and is
    connected to as configured. Raises ConfigError, SessionError or DaemonError.
    """
    if not tool:
        return open_node_session(router)
    security = session_security()
    endpoint = router_endpoint(router, secure=security.secure_default)
    if session_endpoint(router, security=security) == endpoint:
        from ros2lite.daemon.probe import router_answers

        if not router_answers(endpoint, timeout=min(timeout, 0.5)):
            if not autostart:
                raise RouterUnavailableError(endpoint, "nothing listens there")
            from ros2lite.daemon.control import start

            result = start(endpoint, known_absent=True)
            named = started_elsewhere(endpoint, result.pid, secure=security.secure_default)
            if result.started and named is not None:
                _log("warn", named)
    try:
        return open_session(router, mode="client", timeout=timeout, security=security)
    except RouterUnavailableError as exc:
        raise _diagnosed(exc, security) from None


def _diagnosed(
    exc: RouterUnavailableError, security: Security | None = None
) -> RouterUnavailableError:
    """The error, saying why when something does listen at the endpoint (where 'start one
    with daemon start' would only get 'already running' back)."""
    from ros2lite.daemon.probe import not_a_router, router_answers, secured_router, speaks_tls

    if not router_answers(exc.endpoint):
        return exc
    from ros2lite.daemon.control import daemon_pid

    pid = daemon_pid(exc.endpoint)
    better = RouterUnavailableError(exc.endpoint, exc.detail)
    if speaks_tls(exc.endpoint):  # secured, not frozen: this process has no way in
        has_enclave = security is not None and security.credentials is not None
        better.args = (secured_router(exc.endpoint, pid, has_enclave=has_enclave),)
    else:
        better.args = (not_a_router(exc.endpoint, pid),)
    return better
