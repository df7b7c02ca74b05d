"""Timers, fired by the executor when due (steady time, or ROS time under sim time)."""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import TYPE_CHECKING

from ros2lite.executable import Executable

if TYPE_CHECKING:
    from ros2lite.callback_groups import CallbackGroup
    from ros2lite.clock import Clock
    from ros2lite.node import Node
    from ros2lite.task import Task


class Timer(Executable):
    """Calls `callback()` every period; the executor finds it due (no queue entry)."""

    is_timer = True

    def __init__(
        self,
        period_sec: float,
        callback: Callable[[], object],
        clock: Clock | None = None,
        *,
        node: Node | None = None,
        callback_group: CallbackGroup | None = None,
    ) -> None:
        if period_sec < 0:
            raise ValueError('timer period must not be negative')
        super().__init__(node, callback_group)
        self.timer_period_ns = round(period_sec * 1e9)
        self.callback = callback
        self._clock = clock
        self._canceled = False
        self._sim = False  # which time base `_next` is on
        self._next = self._now() + self.timer_period_ns

    def _now(self) -> int:
        """Now on the timer's time base. When `use_sim_time` flips, steady time and ROS time
        are unrelated numbers, so the next call is re-based to one period from now."""
        clock = self._clock
        sim = clock is not None and clock.ros_time_is_active
        # `sim` implies a clock
        now: int = clock.now().nanoseconds if sim else time.monotonic_ns()  # type: ignore[union-attr]
        if sim != self._sim:
            self._sim = sim
            self._next = now + self.timer_period_ns
        return now

    def time_until_next_call(self) -> float | None:
        """Seconds until the timer is due (negative: overdue); None once cancelled."""
        if self._canceled:
            return None
        now = self._now()  # first: it may re-base `_next`
        return (self._next - now) / 1e9

    def is_ready(self) -> bool:
        """Whether the timer is due."""
        remaining = self.time_until_next_call()
        return remaining is not None and remaining <= 0

    @property
    def timer_period_sec(self) -> float:
        """The period in seconds."""
        return self.timer_period_ns / 1e9

    def execute(self) -> None:
        """Fire now (advancing the schedule), on the caller's thread."""
        if self._fire():
            self.callback()

    def _execute(self, batch: bool, stop: Callable[[], bool] | None) -> Task | None:
        return self._call(self.callback) if self._fire() else None

    def _fire(self) -> bool:
        if self._canceled:
            return False
        now = self._now()
        # keep the phase; if we fell behind by whole periods, skip them rather than burst
        self._next += self.timer_period_ns
        if self._next <= now:
            behind = (now - self._next) // max(self.timer_period_ns, 1) + 1
            self._next += behind * self.timer_period_ns
        return True

    def cancel(self) -> None:
        """Stop firing (reset() starts it again)."""
        self._canceled = True

    def is_canceled(self) -> bool:
        """Whether cancel() stopped it."""
        return self._canceled

    def reset(self) -> None:
        """Start again: next due one period from now."""
        self._canceled = False
        self._next = self._now() + self.timer_period_ns
