"""Which router and domain this process talks to, read from the environment ROS users know.

Apart from :mod:`ros2lite.transport.config` because these answers need no zenoh: a graph verb
answered by the daemon's graph cache (:mod:`ros2lite.daemon.graph_cache`) never loads it.
"""

from __future__ import annotations

import os
import re
from collections.abc import Mapping

from ros2lite.transport.errors import ConfigError
from ros2lite.util.domain import parse_domain_id

__all__ = [
    "DEFAULT_ROUTER",
    "DEFAULT_SECURE_ROUTER",
    "DOMAIN_ENV",
    "OVERRIDE_ENV",
    "ROUTER_CHECK_ENV",
    "ROUTER_CONFIG_ENV",
    "ROUTER_ENV",
    "SESSION_CONFIG_ENV",
    "default_router",
    "domain_id",
    "endpoint_host_port",
    "environ",
    "explicit_router",
    "is_local_endpoint",
    "router_check_attempts",
    "router_endpoint",
]

DEFAULT_ROUTER = "tcp/127.0.0.1:7447"
# where the router listens when security is on (same port, TLS with mutual authentication)
DEFAULT_SECURE_ROUTER = "tls/127.0.0.1:7447"
ROUTER_ENV = "ROS2LITE_ROUTER"
SESSION_CONFIG_ENV = "ZENOH_SESSION_CONFIG_URI"
ROUTER_CONFIG_ENV = "ZENOH_ROUTER_CONFIG_URI"
OVERRIDE_ENV = "ZENOH_CONFIG_OVERRIDE"
DOMAIN_ENV = "ROS_DOMAIN_ID"
ROUTER_CHECK_ENV = "ZENOH_ROUTER_CHECK_ATTEMPTS"


def environ(env: Mapping[str, str] | None = None) -> Mapping[str, str]:
    """`env` when given, else the process environment (tests pass their own mapping)."""
    return os.environ if env is None else env


def default_router(secure: bool = False) -> str:
    """The endpoint used when none is named: TLS when this process runs secured (its caller
    knows: see :func:`ros2lite.daemon.connect.secure_default`), plain TCP otherwise."""
    return DEFAULT_SECURE_ROUTER if secure else DEFAULT_ROUTER


def router_endpoint(
    router: str | None = None, env: Mapping[str, str] | None = None, *, secure: bool = False
) -> str:
    """The router endpoint: explicit argument, else ``$ROS2LITE_ROUTER``, else the default
    (TLS when ``secure``)."""
    value = router or environ(env).get(ROUTER_ENV) or default_router(secure)
    value = value.strip()
    if "/" not in value or not value.split("/", 1)[1]:
        raise ConfigError(
            f"bad router endpoint {value!r}: expected <protocol>/<address>, e.g. {DEFAULT_ROUTER}"
        )
    return value


def explicit_router(router: str | None, env: Mapping[str, str] | None = None) -> str | None:
    """The endpoint the caller or ``$ROS2LITE_ROUTER`` named, None when neither did."""
    if router or environ(env).get(ROUTER_ENV):
        return router_endpoint(router, env)
    return None


def domain_id(env: Mapping[str, str] | None = None) -> int:
    """``ROS_DOMAIN_ID`` read as rcl reads it (:func:`parse_domain_id`; unset or empty: 0)."""
    try:
        return parse_domain_id(environ(env).get(DOMAIN_ENV, ""))
    except ValueError as e:
        raise ConfigError(str(e)) from None


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


def is_local_endpoint(endpoint: str) -> bool:
    """Is ``endpoint`` on this host (loopback, a wildcard address or a unix socket)?"""
    if endpoint.partition("/")[0].startswith("unixsock"):
        return True
    parsed = endpoint_host_port(endpoint)
    if parsed is None:
        return False
    host = parsed[1].lower()
    return host in ("localhost", "::1", "::", "0.0.0.0") or host.startswith("127.")


def router_check_attempts(env: Mapping[str, str] | None = None) -> int:
    """``ZENOH_ROUTER_CHECK_ATTEMPTS`` as rmw_zenoh reads it.

    Unset or empty means 1 check; N > 0 means N checks one second apart; 0 means wait until a
    router answers; a negative value skips the check.
    """
    raw = environ(env).get(ROUTER_CHECK_ENV, "").strip()
    if not raw:
        return 1
    try:
        return int(raw)
    except ValueError:
        raise ConfigError(f"{ROUTER_CHECK_ENV} must be an integer, got {raw!r}") from None
