"""Shared measuring helpers for the benchmark modules (`bench_*.py`)."""

from __future__ import annotations

import contextlib
import os
import socket
import subprocess
import time
from collections.abc import Callable, Iterator
from typing import Any


def rate(fn: Callable[[], Any], min_time: float = 0.3, repeats: int = 5) -> float:
    """Best-of-`repeats` calls per second, each repeat running at least `min_time`."""
    n = 1
    while True:
        t0 = time.perf_counter()
        for _ in range(n):
            fn()
        dt = time.perf_counter() - t0
        if dt >= min_time / 4:
            break
        n *= 2
    best = 0.0
    for _ in range(repeats):
        t0 = time.perf_counter()
        for _ in range(n):
            fn()
        best = max(best, n / (time.perf_counter() - t0))
    return best


def report(name: str, value: float, unit: str, ratio: float) -> None:
    print(f'{name} {value:.6g} {unit} {ratio:.3f}', flush=True)


def wall(cmd: list[str], runs: int = 15) -> float:
    """Median wall time of a whole process, in seconds."""
    times = []
    for _ in range(runs):
        t0 = time.perf_counter()
        subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=True)
        times.append(time.perf_counter() - t0)
    times.sort()
    return times[len(times) // 2]


def free_port() -> int:
    with socket.socket() as sock:
        sock.bind(('127.0.0.1', 0))
        return int(sock.getsockname()[1])


def cli_env(endpoint: str, domain: str, runtime: str) -> dict[str, str]:
    """The environment of a measured CLI process: our router and domain, and byte-code
    caching as an installed package has it (pip compiles on install): a private pycache
    prefix, so a PYTHONDONTWRITEBYTECODE shell can't make every run recompile the sources
    (the baseline gets the same treatment)."""
    env = {
        **os.environ,
        'ROS2LITE_ROUTER': endpoint,
        'ROS_DOMAIN_ID': domain,
        'XDG_RUNTIME_DIR': runtime,
        'PYTHONPYCACHEPREFIX': os.path.join(runtime, 'pyc'),
    }
    for var in (
        'ZENOH_CONFIG_OVERRIDE',
        'ZENOH_SESSION_CONFIG_URI',
        'ZENOH_ROUTER_CONFIG_URI',
        'PYTHONDONTWRITEBYTECODE',
    ):
        env.pop(var, None)
    return env


@contextlib.contextmanager
def environment(env: dict[str, str]) -> Iterator[None]:
    """Run the block with exactly `env` as this process' environment."""
    saved = dict(os.environ)
    os.environ.clear()
    os.environ.update(env)
    try:
        yield
    finally:
        os.environ.clear()
        os.environ.update(saved)


def import_click_wall(runs: int = 9) -> float:
    """The CLI baseline: `python -c 'import click'` (cache warmed first)."""
    import sys

    wall([sys.executable, '-c', 'import click'], runs=1)
    return wall([sys.executable, '-c', 'import click'], runs=runs)
