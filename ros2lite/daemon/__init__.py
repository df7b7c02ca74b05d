"""The ros2lite daemon: a Zenoh router (rmw_zenohd-compatible) in a detached process.

``start``/``stop``/``status``/``ensure_running`` are what the CLI's ``daemon`` verbs and
auto-start call.  Names load lazily so ``python -m ros2lite.daemon`` can fork before zenoh
is imported.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from ros2lite.daemon.control import (
        DaemonStatus,
        StartResult,
        StopResult,
        ensure_running,
        start,
        status,
        stop,
    )
    from ros2lite.daemon.errors import DaemonError
    from ros2lite.daemon.paths import runtime_dir
    from ros2lite.daemon.probe import router_answers
    from ros2lite.daemon.router import DaemonInfo

# each name, and the module of this package that defines it
_HOMES = {
    "DaemonError": "errors",
    "DaemonInfo": "router",
    "DaemonStatus": "control",
    "StartResult": "control",
    "StopResult": "control",
    "ensure_running": "control",
    "router_answers": "probe",
    "runtime_dir": "paths",
    "start": "control",
    "status": "control",
    "stop": "control",
}

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
    home = _HOMES.get(name)
    if home is None:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    return getattr(importlib.import_module(f"{__name__}.{home}"), name)
