"""Shared measuring helpers for the benchmark modules (`bench_*.py`)."""

from __future__ import annotations

import subprocess
import time
from collections.abc import Callable
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


