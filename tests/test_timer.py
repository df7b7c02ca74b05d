"""Timers fired by the executor: period, cancel, reset, and skipping missed periods."""

from __future__ import annotations

import itertools
import time
from typing import Any

import pytest

from ros2lite.executors import SingleThreadedExecutor
from ros2lite.node import Node
from ros2lite.timer import Timer
from tests.spinning import spin_for


@pytest.fixture
def node(ros_context: Any) -> Node:
    return Node('timers', context=ros_context)


@pytest.fixture
def executor(ros_context: Any, node: Node) -> SingleThreadedExecutor:
    ex = SingleThreadedExecutor(context=ros_context)
    ex.add_node(node)
    return ex


def test_rate(node: Node, executor: SingleThreadedExecutor) -> None:
    stamps: list[float] = []
    node.create_timer(0.05, lambda: stamps.append(time.monotonic()))
    start = time.monotonic()
    spin_for(executor, 0.52)
    assert 8 <= len(stamps) <= 11
    assert stamps[0] - start == pytest.approx(0.05, abs=0.03)
    gaps = [b - a for a, b in itertools.pairwise(stamps)]
    assert sum(gaps) / len(gaps) == pytest.approx(0.05, abs=0.01)


def test_two_timers_interleave(node: Node, executor: SingleThreadedExecutor) -> None:
    fast: list[int] = []
    slow: list[int] = []
    node.create_timer(0.02, lambda: fast.append(1))
    node.create_timer(0.1, lambda: slow.append(1))
    spin_for(executor, 0.45)
    assert 4 <= len(slow) <= 5
    assert len(fast) >= 4 * len(slow)


def test_cancel_and_reset(node: Node, executor: SingleThreadedExecutor) -> None:
    calls: list[int] = []
    timer = node.create_timer(0.03, lambda: calls.append(1))
    spin_for(executor, 0.1)
    assert calls
    timer.cancel()
    assert timer.is_canceled() and timer.time_until_next_call() is None
    n = len(calls)
    spin_for(executor, 0.15)
    assert len(calls) == n
    timer.reset()
    assert not timer.is_canceled()
    remaining = timer.time_until_next_call()
    assert remaining is not None and 0 < remaining <= 30_000_000
    spin_for(executor, 0.1)
    assert len(calls) > n


def test_destroy_timer(node: Node, executor: SingleThreadedExecutor) -> None:
    calls: list[int] = []
    timer = node.create_timer(0.02, lambda: calls.append(1))
    node.destroy_timer(timer)
    assert timer not in node.timers
    spin_for(executor, 0.1)
    assert calls == []


def test_missed_periods_are_skipped_not_burst() -> None:
    calls: list[int] = []
    timer = Timer(0.01, lambda: calls.append(1))
    time.sleep(0.055)  # five periods late
    assert timer.is_ready()
    timer.execute()
    assert calls == [1] and not timer.is_ready()
    remaining = timer.time_until_next_call()
    assert remaining is not None and 0 < remaining <= 10_000_000


def test_period_validation() -> None:
    with pytest.raises(ValueError):
        Timer(-1.0, lambda: None)
    assert Timer(0.25, lambda: None).timer_period_ns == 250_000_000


def test_switching_time_base_rebases_the_next_call() -> None:
    from ros2lite.clock import ROSClock, Time

    clock = ROSClock()
    timer = Timer(1.0, lambda: None, clock)
    assert timer.time_until_next_call() == pytest.approx(1e9, abs=1e8)
    # use_sim_time on: /clock says 5 s; the steady-time deadline means nothing there
    clock._set_ros_time_is_active(True)
    clock.set_ros_time_override(Time(seconds=5))
    assert timer.time_until_next_call() == pytest.approx(1e9)
    clock.set_ros_time_override(Time(seconds=6))
    assert timer.is_ready()
    timer.execute()
    assert timer.time_until_next_call() == pytest.approx(1e9)
    # and back to steady time: one period from now again, not ~forever or at once
    clock._set_ros_time_is_active(False)
    assert timer.time_until_next_call() == pytest.approx(1e9, abs=1e8)
