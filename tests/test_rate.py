"""Rate: `sleep()` wakes on the ticks of a timer of the node, spun by another thread, and a
destroyed rate wakes its sleepers."""

from __future__ import annotations

import threading
import time
from typing import Any

import pytest

from ros2lite.exceptions import ROSInterruptException
from ros2lite.executors import SingleThreadedExecutor
from ros2lite.node import Node


def test_sleep_keeps_the_period(ros_context: Any) -> None:
    node = Node('rated', context=ros_context)
    executor = SingleThreadedExecutor(context=ros_context)
    executor.add_node(node)
    spinner = threading.Thread(target=executor.spin, daemon=True)
    spinner.start()
    try:
        rate = node.create_rate(20.0)
        rate.sleep()  # the first tick's phase is arbitrary
        start = time.monotonic()
        for _ in range(5):
            time.sleep(0.01)  # work shorter than the period does not add up
            rate.sleep()
        elapsed = time.monotonic() - start
        assert 5 * 0.05 * 0.8 <= elapsed <= 5 * 0.05 + 0.5
        with pytest.raises(TypeError):
            node.create_rate(None)  # type: ignore[arg-type]
        with pytest.raises(ValueError):
            node.create_rate(0.0)
    finally:
        executor.shutdown()
        spinner.join(5)


def test_destroy_wakes_a_sleeper(ros_context: Any) -> None:
    node = Node('slow_rate', context=ros_context)
    rate = node.create_rate(1e-6)
    outcome: list[str] = []

    def sleep() -> None:
        try:
            rate.sleep()
        except ROSInterruptException:
            outcome.append('woken')

    sleeper = threading.Thread(target=sleep)
    sleeper.start()
    time.sleep(0.05)
    assert node.destroy_rate(rate) and not node.destroy_rate(rate)
    sleeper.join(5)
    assert outcome == ['woken']
