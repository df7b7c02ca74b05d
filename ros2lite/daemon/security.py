"""Security, decided once per session here and handed to :mod:`ros2lite.transport` as a value:
every session and router the daemon package opens has its enclave checked the same way
(:func:`ros2lite.security.environment.enclave_problems`). Its own module so that connect.py
(which starts the daemon) and control.py/router.py (the daemon) share it without a circle.
"""

from __future__ import annotations

from collections.abc import Mapping

from ros2lite.security.environment import STRATEGY_ENV, enforced, resolve, security_enabled
from ros2lite.transport.endpoints import router_endpoint
from ros2lite.transport.security import Security

__all__ = ["refuse_plain", "secured_endpoint", "session_security"]


def refuse_plain(env: Mapping[str, str] | None) -> str:
    """Why unencrypted links are refused, '' when they are not (only under Enforce)."""
    return f"{STRATEGY_ENV}=Enforce" if enforced(env) else ""


def session_security(env: Mapping[str, str] | None = None) -> Security:
    """This process's security for its sessions: its enclave's material, checked
    (Enforce without usable material raises SecurityError; Permissive says so once)."""
    return Security(resolve(env), refuse_plain(env))


def secured_endpoint(router: str | None = None, env: Mapping[str, str] | None = None) -> str:
    """The router endpoint: ``router``, else ``$ROS2LITE_ROUTER``, else the default, the TLS
    one when this process runs secured (Enforce, or an enclave it can use)."""
    secure = enforced(env) or (security_enabled(env) and resolve(env) is not None)
    return router_endpoint(router, env, secure=secure)
