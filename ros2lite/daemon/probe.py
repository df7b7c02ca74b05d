"""Is a router there?  Cheap probes used on every CLI call and while starting the daemon."""

from __future__ import annotations

import re
import socket
import time

from ros2lite.transport.endpoints import endpoint_host_port

__all__ = [
    "not_a_router",
    "router_answers",
    "secured_router",
    "speaks_tls",
    "speaks_zenoh",
    "wait_answers",
]


def router_answers(endpoint: str, timeout: float = 0.5) -> bool:
    """Does anything accept connections at ``endpoint``?

    For TCP-based endpoints (tcp, tls, ws) this is a plain TCP connect, which takes a
    millisecond, where opening a Zenoh session takes tens of them and spins up a runtime.
    It cannot tell a Zenoh router from another server on the port; that is an acceptable
    trade for a probe run on every CLI call.  Unix sockets are connected to directly; other
    protocols (udp, quic…) fall back to opening a short-lived Zenoh client session.
    """
    proto = endpoint.partition("/")[0]
    if proto == "unixsock-stream":
        path = re.split(r"[?#]", endpoint.partition("/")[2], maxsplit=1)[0]
        with socket.socket(socket.AF_UNIX, socket.SOCK_STREAM) as sock:
            sock.settimeout(timeout)
            try:
                sock.connect(path)
                return True
            except OSError:
                return False
    parsed = endpoint_host_port(endpoint)
    if parsed is not None and proto in ("tcp", "tls", "ws"):
        _, host, port = parsed
        host = {"0.0.0.0": "127.0.0.1", "::": "::1"}.get(host, host)
        try:
            with socket.create_connection((host, port), timeout=timeout):
                return True
        except OSError:
            return False
    return _zenoh_probe(endpoint, timeout)


def speaks_zenoh(endpoint: str, timeout: float = 1.0) -> bool:
    """Does a Zenoh router answer at `endpoint` (a session completes its handshake)? Dearer
    than :func:`router_answers`: only asked when a listener is there but something is off."""
    return _zenoh_probe(endpoint, timeout)


def speaks_tls(endpoint: str, timeout: float = 1.0) -> bool:
    """Does the listener at `endpoint` (host and port, whatever protocol it names) complete a
    TLS handshake? A secured router does: asked without a client certificate it refuses the
    session, not the handshake, so this tells "secured" apart from "frozen" where opening a
    session cannot. Only asked once a session failed (a zenoh listener on plain TCP keeps
    silent at a ClientHello until `timeout`)."""
    import ssl

    parsed = endpoint_host_port(endpoint)
    if parsed is None:
        return False
    _, host, port = parsed
    host = {"0.0.0.0": "127.0.0.1", "::": "::1"}.get(host, host)
    context = ssl.SSLContext(ssl.PROTOCOL_TLS_CLIENT)
    # only whether it speaks TLS: who it is, the session with a certificate decides
    context.check_hostname = False
    context.verify_mode = ssl.CERT_NONE
    try:
        with (
            socket.create_connection((host, port), timeout=timeout) as raw,
            context.wrap_socket(raw),
        ):
            return True
    except ssl.SSLError as e:
        # TLS 1.2 refuses a missing client certificate inside the handshake, with an alert
        return "ALERT" in str(e.reason or "").upper()
    except OSError:
        return False


def secured_router(endpoint: str, pid: int | None = None, *, has_enclave: bool = False) -> str:
    """What to tell a user whose session a secured router (TLS with client certificates) at
    `endpoint` did not let in: what this process can see of it, and how to join."""
    tls = "tls/" + endpoint.partition("/")[2]
    who = f"The ros2lite daemon (pid {pid})" if pid is not None else "A Zenoh router"
    if has_enclave:
        return (
            f"{who} at {endpoint} is secured (TLS with client certificates) and did not accept "
            "this process's enclave certificate (one from another keystore's CA?): it is "
            "there, but its sessions and graph are not visible from here"
        )
    return (
        f"{who} at {endpoint} is secured (TLS with client certificates); this process runs "
        "unsecured, so it sees that the router is there but not its sessions or graph: to "
        f"join, use {tls} with ROS_SECURITY_ENABLE=true, ROS_SECURITY_KEYSTORE and an enclave "
        "(ROS_SECURITY_ENCLAVE_OVERRIDE or --ros-args --enclave)"
    )


def not_a_router(endpoint: str, pid: int | None = None) -> str:
    """What to tell a user when something listens at `endpoint` but no Zenoh router answers
    (a frozen router, or another program on the port)."""
    if pid is not None:
        return (
            f"The ros2lite daemon (pid {pid}) listens at {endpoint} but does not answer as a "
            "Zenoh router (frozen or overloaded?); 'ros2lite daemon stop' ends it"
        )
    return (
        f"Something listens at {endpoint} but does not answer as a Zenoh router (a frozen "
        "router, or another program on that port): stop it, or choose another endpoint "
        "(ROS2LITE_ROUTER)"
    )


def _zenoh_probe(endpoint: str, timeout: float) -> bool:
    from ros2lite.transport.open import router_reachable

    return router_reachable(endpoint, timeout)


def wait_answers(endpoint: str, timeout: float) -> bool:
    """Whether a router answers at `endpoint` within `timeout` seconds."""
    deadline = time.monotonic() + timeout
    while True:
        if router_answers(endpoint, timeout=0.2):
            return True
        if time.monotonic() >= deadline:
            return False
        time.sleep(0.05)
