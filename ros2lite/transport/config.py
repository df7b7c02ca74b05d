"""Zenoh configuration for ros2lite sessions and routers, from the environment ROS users know.

Sessions run in **client** mode by default, connected to one router.  rmw_zenoh's own sessions
are peers (they listen on loopback and open direct links to every other peer the router
gossips about), which pays off for long-lived nodes moving lots of data.  A ros2lite process is
usually a short CLI call, where client mode is the better fit:

* one TCP link instead of one per ROS process on the host, so opening is quick and cheap;
* nothing listens, so nothing new is exposed;
* delivery never depends on a peer-to-peer link being up: rmw_zenohd runs with
  ``peers_failover_brokering: false``, so a *peer* that has not (yet) linked to another peer
  gets no data from it, while a router always forwards to and from its clients;
* an unreachable router is reported by ``zenoh.open`` itself, so failing fast is easy.

The price is one extra loopback hop through the router.  ``ZENOH_CONFIG_OVERRIDE='mode="peer"'``
switches to rmw_zenoh's peer layout (a loopback listener and the same gossip settings are
already configured for that mode).

Precedence, lowest first: built-in defaults, or the json5 file in ``ZENOH_SESSION_CONFIG_URI``
/ ``ZENOH_ROUTER_CONFIG_URI`` instead of them (as rmw_zenoh does); ``ROS2LITE_ROUTER``;
``ZENOH_CONFIG_OVERRIDE``; and last the explicit ``router=`` argument (the CLI's
``--router``), because a flag typed on the command line should beat the environment.
"""

from __future__ import annotations

import json
import os
import re
import time
from collections.abc import Mapping, Sequence

import zenoh

__all__ = [
    "DEFAULT_ROUTER",
    "ROUTER_ENV",
    "ConfigError",
    "RouterUnavailableError",
    "SessionError",
    "apply_config_override",
    "default_listen",
    "domain_id",
    "endpoint_host_port",
    "open_session",
    "parse_config_override",
    "router_config",
    "router_endpoint",
    "session_config",
    "zerror_message",
]

DEFAULT_ROUTER = "tcp/127.0.0.1:7447"
ROUTER_ENV = "ROS2LITE_ROUTER"
SESSION_CONFIG_ENV = "ZENOH_SESSION_CONFIG_URI"
ROUTER_CONFIG_ENV = "ZENOH_ROUTER_CONFIG_URI"
OVERRIDE_ENV = "ZENOH_CONFIG_OVERRIDE"
DOMAIN_ENV = "ROS_DOMAIN_ID"
MAX_DOMAIN_ID = 232

# How long zenoh may keep retrying the router at open; short, because a router that is
# starting is waited for by the daemon code before a session is ever opened.
CONNECT_TIMEOUT_MS = 1000


class ConfigError(ValueError):
    """A bad environment variable, config file or override; the message says which."""


class SessionError(RuntimeError):
    """A Zenoh session could not be opened (other than for a missing router)."""


class RouterUnavailableError(SessionError):
    """No Zenoh router answers at the endpoint a session was told to use."""

    def __init__(self, endpoint: str, detail: str = "") -> None:
        self.endpoint = endpoint
        self.detail = detail
        super().__init__(
            f"No Zenoh router answers at {endpoint} (start one with 'ros2lite daemon start')"
        )


def _env(env: Mapping[str, str] | None) -> Mapping[str, str]:
    return os.environ if env is None else env


def zerror_message(exc: BaseException) -> str:
    """A zenoh error as one readable line (without the trailing ' at /…/file.rs:NN.')."""
    text = re.sub(r"\s+at /\S+?\.rs:\d+\.?", "", str(exc).strip())
    m = re.search(r'msg: "(.*?)", location', text) or re.fullmatch(r'Str\("(.*)"\)', text)
    return (m.group(1) if m else text).rstrip(". ")


def router_endpoint(router: str | None = None, env: Mapping[str, str] | None = None) -> str:
    """The router endpoint: explicit argument, else ``$ROS2LITE_ROUTER``, else the default."""
    value = router or _env(env).get(ROUTER_ENV) or DEFAULT_ROUTER
    value = value.strip()
    if "/" not in value or not value.split("/", 1)[1]:
        raise ConfigError(
            f"bad router endpoint {value!r}: expected <protocol>/<address>, "
            f"e.g. {DEFAULT_ROUTER}"
        )
    return value


def _explicit_router(router: str | None, env: Mapping[str, str] | None) -> str | None:
    if router or _env(env).get(ROUTER_ENV):
        return router_endpoint(router, env)
    return None


def domain_id(env: Mapping[str, str] | None = None) -> int:
    """``ROS_DOMAIN_ID`` (default 0), checked to be an integer in 0..232."""
    raw = _env(env).get(DOMAIN_ENV, "").strip()
    if not raw:
        return 0
    try:
        value = int(raw)
    except ValueError:
        raise ConfigError(
            f"ROS_DOMAIN_ID must be an integer in 0..{MAX_DOMAIN_ID}, got {raw!r}"
        ) from None
    if not 0 <= value <= MAX_DOMAIN_ID:
        raise ConfigError(f"ROS_DOMAIN_ID must be in 0..{MAX_DOMAIN_ID}, got {value}")
    return value


def endpoint_host_port(endpoint: str) -> tuple[str, str, int] | None:
    """Split ``tcp/127.0.0.1:7447`` into (``tcp``, ``127.0.0.1``, 7447); None if not host:port.

    Bracketed IPv6 (``tcp/[::1]:7447``) is unwrapped; ``?metadata`` and ``#config`` are ignored.
    """
    proto, sep, rest = endpoint.partition("/")
    if not sep:
        return None
    rest = re.split(r"[?#]", rest, maxsplit=1)[0]
    m = re.fullmatch(r"\[([^\]]+)\]:(\d+)|([^:\[\]]+):(\d+)", rest)
    if not m:
        return None
    host = m.group(1) or m.group(3)
    port = int(m.group(2) or m.group(4))
    return proto, host, port


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


def session_config(router: str | None = None, env: Mapping[str, str] | None = None) -> zenoh.Config:
    """The config for one ros2lite session (see the module docstring for the choices)."""
    environ = _env(env)
    config = _load_file(SESSION_CONFIG_ENV, environ)
    endpoint = _explicit_router(None, env)  # ROS2LITE_ROUTER only; router= goes last
    if config is None:
        config = zenoh.Config()
        endpoint = endpoint or router_endpoint(None, env)
        defaults = [
            ("mode", '"client"'),
            # Clients ignore "listen"; a peer (via override) listens on loopback like rmw_zenoh.
            ("listen/endpoints", '{peer: ["tcp/127.0.0.1:0"]}'),
            ("connect/exit_on_failure", "true"),
            ("connect/timeout_ms", str(CONNECT_TIMEOUT_MS)),
            ("scouting/multicast/enabled", "false"),
            ("scouting/gossip/enabled", "true"),
            ("scouting/gossip/target", '{router: ["router", "peer"], peer: ["router"]}'),
            ("scouting/gossip/autoconnect", '{router: [], peer: ["router", "peer"]}'),
            ("scouting/gossip/autoconnect_strategy",
             '{peer: {to_router: "always", to_peer: "greater-zid"}}'),
            ("timestamping/enabled", "true"),
            ("queries_default_timeout", "600000"),
            ("transport/shared_memory/enabled", "false"),
        ]
        for key, value in defaults:
            _insert(config, key, value, "built-in session config")
    if endpoint:
        _insert(config, "connect/endpoints", _endpoints_json([endpoint]), ROUTER_ENV)
    apply_config_override(config, env=env)
    if router:
        _insert(config, "connect/endpoints", _endpoints_json([router_endpoint(router)]), "router")
    return config


def router_config(
    router: str | None = None,
    listen: Sequence[str] | None = None,
    connect: Sequence[str] = (),
    env: Mapping[str, str] | None = None,
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
        env_listen = default_listen(router_endpoint(None, env))
        defaults = [
            ("mode", '"router"'),
            ("scouting/multicast/enabled", "false"),
            ("scouting/gossip/enabled", "true"),
            ("scouting/gossip/multihop", "false"),
            ("routing/router/peers_failover_brokering", "false"),
            ("timestamping/enabled", "true"),
            ("transport/shared_memory/enabled", "false"),
        ]
        for key, value in defaults:
            _insert(config, key, value, "built-in router config")
    elif _explicit_router(None, env):
        env_listen = default_listen(router_endpoint(None, env))
    if env_listen:
        _insert(config, "listen/endpoints", _endpoints_json(env_listen), "listen endpoints")
    apply_config_override(config, env=env)
    if not listen and router:
        listen = default_listen(router_endpoint(router))
    if listen:
        _insert(config, "listen/endpoints", _endpoints_json(listen), "listen endpoints")
    if connect:
        _insert(config, "connect/endpoints", _endpoints_json(connect), "connect endpoints")
    return config


def _configured_endpoint(config: zenoh.Config, fallback: str) -> str:
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


def open_session(
    router: str | None = None,
    *,
    timeout: float = 1.0,
    require_router: bool = True,
    env: Mapping[str, str] | None = None,
) -> zenoh.Session:
    """Open a zenoh session for ros2lite and make sure a router is really there.

    zenoh-python behaves differently per mode when the router is down: a client fails in
    ``zenoh.open`` (after ``connect/timeout_ms``), but a peer opens anyway with no router
    and just hears nothing.  So after opening we also wait up to ``timeout`` seconds for
    ``session.info.routers_zid()`` to list one, and raise :class:`RouterUnavailableError`
    (one clear line) otherwise.
    """
    config = session_config(router, env)
    endpoint = _configured_endpoint(config, router_endpoint(router, env))
    try:
        session = zenoh.open(config)
    except zenoh.ZError as exc:
        detail = zerror_message(exc)
        if "connect" in detail.lower():
            raise RouterUnavailableError(endpoint, detail) from None
        raise SessionError(f"cannot open a Zenoh session: {detail}") from None
    if not require_router:
        return session
    deadline = time.monotonic() + timeout
    while not session.info.routers_zid():
        if time.monotonic() >= deadline:
            session.close()
            raise RouterUnavailableError(endpoint, "session opened but no router is connected")
        time.sleep(0.02)
    return session
