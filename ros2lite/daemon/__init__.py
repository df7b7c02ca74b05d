"""The ros2lite daemon: a Zenoh router (rmw_zenohd-compatible) in a detached process.

``start``/``stop``/``status``/``ensure_running`` are what the CLI's ``daemon`` verbs and
auto-start call.  Names load lazily so ``python -m ros2lite.daemon`` can fork before zenoh
is imported.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from ros2lite.daemon.paths import runtime_dir
    from ros2lite.daemon.router import (
        DaemonError,
        DaemonInfo,
        DaemonStatus,
        StartResult,
        StopResult,
        ensure_running,
        router_answers,
        start,
        status,
        stop,
    )

__all__ = [
    "DaemonError",
    "DaemonInfo",
    "DaemonStatus",
    "StartResult",
    "StopResult",
    "ensure_running",
    "router_answers",
    "runtime_dir",
    "start",
    "status",
    "stop",
]


def __getattr__(name: str) -> Any:
    if name == "runtime_dir":
        from ros2lite.daemon.paths import runtime_dir

        return runtime_dir
    if name in __all__:
        from ros2lite.daemon import router

        return getattr(router, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
