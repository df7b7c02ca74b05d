"""Timers, fired by the executor when due (steady time, or ROS time under sim time)."""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import TYPE_CHECKING, Protocol

from ros2lite.runtime.executable import EntityNode, Executable

if TYPE_CHECKING:
    from ros2lite.callback_groups import CallbackGroup
    from ros2lite.clock import Clock
    from ros2lite.task import Task


class TimerNode(EntityNode, Protocol):
    """The node of a timer (:class:`ros2lite.node.Node`): it keeps its timers in a list."""

    timers: list[Timer]


class Timer(Executable):
    """Calls `callback()` every period; the executor finds it due (no queue entry)."""

    is_timer = True
    _node: TimerNode | None

    def __init__(
        self,
        period_sec: float,
        callback: Callable[[], object],
        clock: Clock | None = None,
        *,
        node: TimerNode | None = None,
        callback_group: CallbackGroup | None = None,
        autostart: bool = True,
    ) -> None:
        if period_sec < 0:
            raise ValueError('timer period must not be negative')
        super().__init__(node, callback_group)
        self._period_ns = round(period_sec * 1e9)
        self.callback = callback
        self._clock = clock
        self._canceled = not autostart
        self._sim = False  # which time base `_next` is on
        self._next = self._now() + self._period_ns
        self._last_call = self._next - self._period_ns

    @property
    def clock(self) -> Clock | None:
        """The clock whose time the period is measured in (None: steady time)."""
        return self._clock

    @property
    def timer_period_ns(self) -> int:
        """The period in nanoseconds."""
        return self._period_ns

    @timer_period_ns.setter
    def timer_period_ns(self, value: int) -> None:
        """A new period, counted from now (as rcl's timer_exchange_period does not, the next
        call is re-planned so that a longer period is not cut short)."""
        if value < 0:
            raise ValueError('timer period must not be negative')
        self._period_ns = int(value)
        self._next = self._now() + self._period_ns

    def _now(self) -> int:
        """Now on the timer's time base. When `use_sim_time` flips, steady time and ROS time
        are unrelated numbers, so the next call is re-based to one period from now."""
        clock = self._clock
        sim = clock is not None and clock.ros_time_is_active
        # `sim` implies a clock
        now: int = clock.now().nanoseconds if sim else time.monotonic_ns()  # type: ignore[union-attr]
        if sim != self._sim:
            self._sim = sim
            self._next = now + self._period_ns
        return now

    def time_until_next_call(self) -> int | None:
        """Nanoseconds until the timer is due (negative: overdue); None once canceled."""
        if self._canceled:
            return None
        now = self._now()  # first: it may re-base `_next`
        return self._next - now

    def time_since_last_call(self) -> int:
        """Nanoseconds since the timer last fired (or was started)."""
        return self._now() - self._last_call

    def is_ready(self) -> bool:
        """Whether the timer is due."""
        remaining = self.time_until_next_call()
        return remaining is not None and remaining <= 0

    @property
    def timer_period_sec(self) -> float:
        """The period in seconds."""
        return self._period_ns / 1e9

    def execute(self) -> None:
        """Fire now (advancing the schedule), on the caller's thread."""
        if self._fire():
            self.callback()

    def run_pending(self, batch: bool, stop: Callable[[], bool] | None) -> Task | None:
        return self._call(self.callback) if self._fire() else None

    def _fire(self) -> bool:
        if self._canceled:
            return False
        now = self._now()
        self._last_call = now
        # keep the phase; if we fell behind by whole periods, skip them rather than burst
        self._next += self._period_ns
        if self._next <= now:
            behind = (now - self._next) // max(self._period_ns, 1) + 1
            self._next += behind * self._period_ns
        return True

    def cancel(self) -> None:
        """Stop firing (reset() starts it again)."""
        self._canceled = True

    def is_canceled(self) -> bool:
        """Whether cancel() stopped it."""
        return self._canceled

    def reset(self) -> None:
        """Start again: due one period from now (also after cancel())."""
        self._canceled = False
        self._next = self._now() + self._period_ns
        if self._node is not None:
            self._node.work.wake()  # a spinning executor must see the new deadline

    def destroy(self) -> None:
        """Never fire again (the node forgets it too)."""
        self._canceled = True
        if self._node is not None and self in self._node.timers:
            self._node.timers.remove(self)
