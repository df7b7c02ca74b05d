"""Zenoh configuration for ros2lite sessions and routers, from the environment ROS users know.

Two session modes, chosen by what the process is:

* **Nodes** (the client library, ``run``, demos) open **peer** sessions, as rmw_zenoh's own
  nodes do: they connect to the router for discovery (gossip), listen on an ephemeral loopback
  port, and open direct links to every peer the router introduces.  Data then flows peer to
  peer, so established peers keep talking when the router stops or restarts.  They retry the
  router every :data:`RETRY_MAX_MS` at most, so discovery is back well within a second of its
  return, and a peer opens even when no router answers yet (the caller decides what to do
  about that: see :func:`router_check_attempts` and :mod:`ros2lite.daemon.connect`).
  When the router is not on this host a node falls back to client mode: our peers only listen
  on loopback, and rmw_zenohd does not broker data between peers that cannot reach each other.
* **Short CLI verbs** stay **clients**: one TCP link, nothing listening, delivery through the
  router (which always forwards to and from its clients), and ``zenoh.open`` itself reports a
  missing router, so failing fast is easy.

``ZENOH_CONFIG_OVERRIDE='mode="client"'`` (or ``"peer"``) forces a mode for every session. A
verb given a node's peer-mode file opens it as a client (:func:`_tool_as_client` says why).

Precedence, lowest first: built-in defaults, or the json5 file in ``ZENOH_SESSION_CONFIG_URI``
/ ``ZENOH_ROUTER_CONFIG_URI`` instead of them (as rmw_zenoh does); ``ROS2LITE_ROUTER``;
``ZENOH_CONFIG_OVERRIDE``; and last the explicit ``router=`` argument (the CLI's
``--router``), because a flag typed on the command line should beat the environment.

Security arrives as a :class:`~ros2lite.transport.security.Security` value (``security=``),
decided by :mod:`ros2lite.security` for the caller (:mod:`ros2lite.daemon.connect`); without
one a config is unsecured.
"""

from __future__ import annotations

import json
import os
from collections.abc import Mapping, Sequence
from typing import Literal

import zenoh

from ros2lite.transport.endpoints import (
    DEFAULT_ROUTER,
    DEFAULT_SECURE_ROUTER,
    OVERRIDE_ENV,
    ROUTER_CONFIG_ENV,
    ROUTER_ENV,
    SESSION_CONFIG_ENV,
    domain_id,
    endpoint_host_port,
    explicit_router,
    is_local_endpoint,
    router_check_attempts,
    router_endpoint,
)
from ros2lite.transport.endpoints import (
    environ as _env,
)
from ros2lite.transport.errors import (
    ConfigError,
    InsecureLinkError,
    RouterUnavailableError,
    SessionError,
    zerror_message,
)
from ros2lite.transport.security import (
    UNSECURED,
    Security,
    apply_access_control,
    apply_tls,
    is_tls_endpoint,
)

__all__ = [
    "DEFAULT_ROUTER",
    "DEFAULT_SECURE_ROUTER",
    "ROUTER_ENV",
    "ConfigError",
    "RouterUnavailableError",
    "SessionError",
    "SessionMode",
    "apply_config_override",
    "configured_endpoint",
    "configured_mode",
    "default_listen",
    "domain_id",
    "endpoint_host_port",
    "is_local_endpoint",
    "node_session_mode",
    "parse_config_override",
    "router_check_attempts",
    "router_config",
    "router_endpoint",
    "session_config",
    "session_endpoint",
    "zerror_message",
]

SessionMode = Literal["peer", "client"]

# How long zenoh may keep retrying the router at open; short, because a router that is
# starting is waited for by the daemon code before a session is ever opened.
CONNECT_TIMEOUT_MS = 1000
# How often a session retries a router it lost (or never reached): zenoh's default backs off
# to 4 s, which is what made discovery take ~3.5 s after a router restart.  A refused loopback
# connect costs microseconds, so retrying often is cheap.
RETRY_INIT_MS = 100
RETRY_MAX_MS = 400


def default_listen(endpoint: str) -> list[str]:
    """Where a router for ``endpoint`` listens: just there (loopback stays loopback)."""
    return [endpoint]


def parse_config_override(text: str) -> list[tuple[str, str]]:
    """Split ``key=json5;key2=json5`` into pairs.

    ';' inside quotes or brackets does not split, so values like ``["a;b"]`` survive (rmw
    splits naively; for every value it accepts the result is the same).
    """
    pairs: list[tuple[str, str]] = []
    segments: list[str] = []
    buf: list[str] = []
    depth, quote, escaped = 0, "", False
    for ch in text:
        if quote:
            buf.append(ch)
            if escaped:
                escaped = False
            elif ch == "\\":
                escaped = True
            elif ch == quote:
                quote = ""
            continue
        if ch in "\"'":
            quote = ch
        elif ch in "[{":
            depth += 1
        elif ch in "]}":
            depth = max(0, depth - 1)
        elif ch == ";" and depth == 0:
            segments.append("".join(buf))
            buf = []
            continue
        buf.append(ch)
    segments.append("".join(buf))
    for seg in segments:
        seg = seg.strip()
        if not seg:
            continue
        key, eq, value = seg.partition("=")
        key, value = key.strip(), value.strip()
        if not eq or not key or not value:
            raise ConfigError(
                f"bad {OVERRIDE_ENV} entry {seg!r}: expected key=json5 (e.g. mode=\"client\")"
            )
        pairs.append((key, value))
    return pairs


def _insert(config: zenoh.Config, key: str, value: str, origin: str) -> None:
    try:
        config.insert_json5(key, value)
    except zenoh.ZError as exc:
        raise ConfigError(f"{origin}: cannot set {key}={value}: {zerror_message(exc)}") from None


def apply_config_override(
    config: zenoh.Config, text: str | None = None, env: Mapping[str, str] | None = None
) -> None:
    """Apply ``ZENOH_CONFIG_OVERRIDE`` (or ``text``) to ``config`` with ``insert_json5``."""
    if text is None:
        text = _env(env).get(OVERRIDE_ENV, "")
    for key, value in parse_config_override(text):
        _insert(config, key, value, OVERRIDE_ENV)


def _load_file(var: str, env: Mapping[str, str]) -> zenoh.Config | None:
    path = env.get(var, "").strip()
    if not path:
        return None
    if not os.path.isfile(path):
        raise ConfigError(f"{var} points to {path!r}, which is not a readable file")
    try:
        return zenoh.Config.from_file(path)
    except zenoh.ZError as exc:
        raise ConfigError(f"{var}: cannot load {path!r}: {zerror_message(exc)}") from None


def _endpoints_json(endpoints: Sequence[str]) -> str:
    return json.dumps(list(endpoints))


def node_session_mode(
    router: str | None = None,
    env: Mapping[str, str] | None = None,
    *,
    security: Security = UNSECURED,
) -> SessionMode:
    """The mode a long-lived node opens: peer when the router it connects to (after config
    files and overrides) is on this host, else client."""
    endpoint = session_endpoint(router, env, security=security)
    return "peer" if is_local_endpoint(endpoint) else "client"


def session_config(
    router: str | None = None,
    env: Mapping[str, str] | None = None,
    *,
    mode: SessionMode = "client",
    security: Security = UNSECURED,
) -> zenoh.Config:
    """The config for one ros2lite session (see the module docstring for the choices)."""
    environ = _env(env)
    config = _load_file(SESSION_CONFIG_ENV, environ)
    endpoint = explicit_router(None, env)  # ROS2LITE_ROUTER only; router= goes last
    if config is None:
        config = zenoh.Config()
        endpoint = endpoint or router_endpoint(None, env, secure=security.secure_default)
        retry = (
            f"{{period_init_ms: {RETRY_INIT_MS}, period_max_ms: {RETRY_MAX_MS}, "
            "period_increase_factor: 2}"
        )
        defaults = [
            ("mode", json.dumps(mode)),
            # Clients ignore "listen"; a peer listens on loopback like rmw_zenoh's sessions.
            ("listen/endpoints", '{peer: ["tcp/127.0.0.1:0"]}'),
            # A client fails fast without a router; a peer opens anyway and keeps retrying.
            ("connect/exit_on_failure", "{router: false, peer: false, client: true}"),
            ("connect/timeout_ms", f"{{router: -1, peer: -1, client: {CONNECT_TIMEOUT_MS}}}"),
            ("connect/retry", retry),
            ("scouting/multicast/enabled", "false"),
            ("scouting/gossip/enabled", "true"),
            ("scouting/gossip/target", '{router: ["router", "peer"], peer: ["router"]}'),
            ("scouting/gossip/autoconnect", '{router: [], peer: ["router", "peer"]}'),
            (
                "scouting/gossip/autoconnect_strategy",
                '{peer: {to_router: "always", to_peer: "greater-zid"}}',
            ),
            ("timestamping/enabled", "true"),
            ("queries_default_timeout", "600000"),
            ("transport/shared_memory/enabled", "false"),
        ]
        for key, value in defaults:
            _insert(config, key, value, "built-in session config")
    elif mode == "client":
        _tool_as_client(config)
    if endpoint:
        _insert(config, "connect/endpoints", _endpoints_json([endpoint]), ROUTER_ENV)
    if security.credentials is not None:
        # this process's enclave certificate on every TLS link, and client mode, so all
        # traffic crosses the router that enforces the permissions (a peer-to-peer link
        # would bypass it)
        apply_tls(config, security.credentials)
        _insert(config, "mode", '"client"', "security")
    apply_config_override(config, env=env)
    if router:
        _insert(config, "connect/endpoints", _endpoints_json([router_endpoint(router)]), "router")
    if security.credentials is not None:
        _require_tls(config, "connect/endpoints", security)
    return config


def _tool_as_client(config: zenoh.Config) -> None:
    """A short-lived tool given a node's peer-mode file (rmw_zenoh's own session config)
    opens as a client of the same router.

    A peer hears other peers' tokens only over direct links, which gossip opens and fill
    some time after ``zenoh.open`` returns, and no signal says when that view is complete: a
    one-shot `node list` then answers from part of the graph (measured 2 runs in 6). A
    client's query is answered by its router for the whole graph. Left as it is: a file for
    peers without a router (multicast scouting on, or nothing to connect to), and a mode that
    ``ZENOH_CONFIG_OVERRIDE`` sets (applied after this).
    """
    try:
        mode = json.loads(config.get_json("mode")) or "peer"
        multicast = json.loads(config.get_json("scouting/multicast/enabled"))
        connect = json.loads(config.get_json("connect/endpoints"))
    except (zenoh.ZError, ValueError, TypeError):
        return
    if isinstance(connect, dict):  # the per-mode form: a client connects where a peer would
        if connect.get("client") or not connect.get("peer"):
            connect = connect.get("client")
        else:
            _insert(
                config,
                "connect/endpoints",
                json.dumps({**connect, "client": connect["peer"]}),
                "a tool's session",
            )
            connect = connect["peer"]
    if mode != "peer" or multicast is not False or not connect:
        return
    _insert(config, "mode", '"client"', "a tool's session")


def _require_tls(config: zenoh.Config, key: str, security: Security) -> None:
    """When security says so (Enforce), a link that is not TLS is refused in one line."""
    if not security.refuse_plain:
        return
    try:
        value = json.loads(config.get_json(key))
    except (zenoh.ZError, ValueError, TypeError):
        return
    if isinstance(value, dict):
        value = [e for endpoints in value.values() for e in endpoints or []]
    for endpoint in value or []:
        if not is_tls_endpoint(str(endpoint)):
            raise InsecureLinkError(
                f"SECURITY ERROR: {security.refuse_plain} refuses the unencrypted endpoint "
                f"{endpoint}; use a tls/ endpoint (e.g. {DEFAULT_SECURE_ROUTER})"
            )


def router_config(
    router: str | None = None,
    listen: Sequence[str] | None = None,
    connect: Sequence[str] = (),
    env: Mapping[str, str] | None = None,
    *,
    security: Security = UNSECURED,
) -> zenoh.Config:
    """The config for the ros2lite daemon's router (rmw_zenohd's settings, loopback by default).

    ``listen`` defaults to the router endpoint itself; ``connect`` lists other routers to
    mesh with.  ``ZENOH_ROUTER_CONFIG_URI`` replaces the built-in defaults (keeping its own
    listen endpoints unless a router endpoint is named explicitly); ``ZENOH_CONFIG_OVERRIDE``
    comes next and explicit ``router``/``listen``/``connect`` arguments last.
    """
    environ = _env(env)
    config = _load_file(ROUTER_CONFIG_ENV, environ)
    env_listen: list[str] = []
    if config is None:
        config = zenoh.Config()
        env_listen = default_listen(router_endpoint(None, env, secure=security.secure_default))
        defaults = [
            ("mode", '"router"'),
            ("scouting/multicast/enabled", "false"),
            ("scouting/gossip/enabled", "true"),
            ("scouting/gossip/multihop", "false"),
            ("routing/router/peers_failover_brokering", "false"),
            ("timestamping/enabled", "true"),
            # read-only: `daemon status`/`stop` list the connected sessions from it
            ("adminspace/enabled", "true"),
            ("adminspace/permissions", "{read: true, write: false}"),
            ("transport/shared_memory/enabled", "false"),
        ]
        for key, value in defaults:
            _insert(config, key, value, "built-in router config")
    elif explicit_router(None, env):
        env_listen = default_listen(router_endpoint(None, env))  # ROS2LITE_ROUTER: named
    if env_listen:
        _insert(config, "listen/endpoints", _endpoints_json(env_listen), "listen endpoints")
    apply_config_override(config, env=env)
    if not listen and router:
        listen = default_listen(router_endpoint(router))
    if listen:
        _insert(config, "listen/endpoints", _endpoints_json(listen), "listen endpoints")
    if connect:
        _insert(config, "connect/endpoints", _endpoints_json(connect), "connect endpoints")
    if security.credentials is not None:
        # the router's own enclave on its TLS links, and access control made from every
        # enclave's permissions in the keystore (default deny)
        apply_tls(config, security.credentials)
        if security.access is not None:
            apply_access_control(config, security.access)
        _require_tls(config, "listen/endpoints", security)
        _require_tls(config, "connect/endpoints", security)
    return config


def configured_endpoint(config: zenoh.Config, fallback: str) -> str:
    """The connect endpoint(s) the session will use, for error messages."""
    try:
        value = json.loads(config.get_json("connect/endpoints"))
        mode = json.loads(config.get_json("mode")) or "peer"
    except (zenoh.ZError, ValueError, TypeError):
        return fallback
    if isinstance(value, dict):  # the per-mode form {client: [...], peer: [...]}
        value = value.get(mode, [])
    if isinstance(value, list) and value:
        return ", ".join(str(v) for v in value)
    return fallback


def configured_mode(config: zenoh.Config) -> str:
    """The mode a config will open in (after files and overrides), 'peer' if unset."""
    try:
        return str(json.loads(config.get_json("mode")) or "peer")
    except (zenoh.ZError, ValueError, TypeError):
        return "peer"


def session_endpoint(
    router: str | None = None,
    env: Mapping[str, str] | None = None,
    *,
    security: Security = UNSECURED,
) -> str:
    """The router endpoint(s) a session would connect to, as one line for messages."""
    config = session_config(router, env, security=security)
    fallback = router_endpoint(router, env, secure=security.secure_default)
    return configured_endpoint(config, fallback)
