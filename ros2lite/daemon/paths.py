"""Where the daemon of an endpoint keeps its files: pid (and liveness lock), log, start lock
and the graph cache's socket, one set per router endpoint in the user's private runtime dir.

Apart from :mod:`ros2lite.daemon.control` so that finding them loads no zenoh.
"""

from __future__ import annotations

import os
import re
from pathlib import Path

__all__ = ["graph_socket", "lock_file", "log_file", "pid_file", "runtime_dir", "stem"]


def runtime_dir() -> Path:
    """Per-user directory for pid, lock and log files (created 0700 on first use).

    ``$XDG_RUNTIME_DIR/ros2lite`` only when both are ours and closed to others; a shared or
    foreign one falls back to ``~/.cache/ros2lite``
    (see :func:`ros2lite.util.files.private_dir`)."""
    from ros2lite.util.files import private_dir

    return private_dir(os.environ.get("XDG_RUNTIME_DIR", ""))


def stem(endpoint: str) -> str:
    """The file-name stem of an endpoint's files (daemons on different ports coexist)."""
    return "router-" + re.sub(r"[^A-Za-z0-9.:_-]", "_", endpoint)


def pid_file(endpoint: str) -> Path:
    """The daemon's pid and lock file for an endpoint."""
    return runtime_dir() / (stem(endpoint) + ".pid")


def log_file(endpoint: str) -> Path:
    """The daemon's log file for an endpoint."""
    return runtime_dir() / (stem(endpoint) + ".log")


def lock_file(endpoint: str) -> Path:
    """The file that serialises starting and stopping the daemon of an endpoint."""
    return runtime_dir() / (stem(endpoint) + ".lock")


def graph_socket(endpoint: str) -> Path:
    """The Unix socket where the daemon serves its graph cache."""
    return runtime_dir() / (stem(endpoint) + ".sock")
