"""Clocks as rclpy has them: system, steady and ROS time, time-jump callbacks, and sleeping on
any of them.

A ROS clock reads system time until ROS time is made active (by a
:class:`~ros2lite.time_source.TimeSource` when ``use_sim_time`` is set); from then on it reads
the last time set with :meth:`ROSClock.set_ros_time_override` (from ``/clock``). Changes of
either kind are time jumps: callbacks registered with a :class:`JumpThreshold` run before
(`pre_callback()`) and after (`post_callback(TimeJump)`) the change, on the thread making it.
"""

from __future__ import annotations

import enum
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING

from ros2lite.context import default_context
from ros2lite.duration import Duration
from ros2lite.exceptions import NotInitializedException
from ros2lite.time import ClockType, Time

if TYPE_CHECKING:
    from ros2lite.context import Context

__all__ = [
    'Clock',
    'ClockChange',
    'ClockType',
    'Duration',
    'JumpHandle',
    'JumpThreshold',
    'ROSClock',
    'Time',
    'TimeJump',
]


class ClockChange(enum.IntEnum):
    """What kind of time jump happened (rcl_clock_change_t)."""

    ROS_TIME_NO_CHANGE = 1
    ROS_TIME_ACTIVATED = 2
    ROS_TIME_DEACTIVATED = 3
    SYSTEM_TIME_NO_CHANGE = 4


@dataclass(frozen=True)
class TimeJump:
    """Given to post-jump callbacks: the kind of change and how far time moved."""

    clock_change: ClockChange
    delta: Duration


class JumpThreshold:
    """Which jumps a callback wants: forward by at least `min_forward`, backward by at least
    `-min_backward` (a negative duration), and/or ROS time switching on or off."""

    def __init__(
        self,
        *,
        min_forward: Duration | None,
        min_backward: Duration | None,
        on_clock_change: bool = True,
    ) -> None:
        if min_forward is not None and min_forward.nanoseconds <= 0:
            raise ValueError('min_forward must be a positive duration (or None)')
        if min_backward is not None and min_backward.nanoseconds >= 0:
            raise ValueError('min_backward must be a negative duration (or None)')
        if min_forward is None and min_backward is None and not on_clock_change:
            raise ValueError('At least one of the jump thresholds must be enabled')
        self.min_forward = min_forward
        self.min_backward = min_backward
        self.on_clock_change = on_clock_change

    def exceeded(self, jump: TimeJump) -> bool:
        """Whether `jump` is one this threshold selects."""
        if jump.clock_change in (ClockChange.ROS_TIME_ACTIVATED, ClockChange.ROS_TIME_DEACTIVATED):
            return self.on_clock_change
        delta = jump.delta.nanoseconds
        if self.min_forward is not None and delta > 0 and delta >= self.min_forward.nanoseconds:
            return True
        return (
            self.min_backward is not None and delta < 0 and delta <= self.min_backward.nanoseconds
        )


class JumpHandle:
    """A registered jump callback; `unregister()` (or leaving its `with` block) removes it."""

    def __init__(
        self,
        forget: Callable[[JumpHandle], None],
        threshold: JumpThreshold,
        pre_callback: Callable[[], object] | None,
        post_callback: Callable[[TimeJump], object] | None,
    ) -> None:
        self._forget: Callable[[JumpHandle], None] | None = forget  # the clock's
        self.threshold = threshold
        self.pre_callback = pre_callback
        self.post_callback = post_callback

    def unregister(self) -> None:
        """Stop calling the callbacks (again: nothing happens)."""
        forget, self._forget = self._forget, None
        if forget is not None:
            forget(self)

    def __enter__(self) -> JumpHandle:
        return self

    def __exit__(self, *exc: object) -> None:
        self.unregister()


class Clock:
    """Reads time of one clock type; `Clock(clock_type=ClockType.ROS_TIME)` is a ROSClock."""

    def __new__(cls, *, clock_type: ClockType = ClockType.SYSTEM_TIME) -> Clock:
        if cls is Clock and clock_type == ClockType.ROS_TIME:
            cls = ROSClock
        return super().__new__(cls)

    def __init__(self, *, clock_type: ClockType = ClockType.SYSTEM_TIME) -> None:
        if not isinstance(clock_type, ClockType):
            raise TypeError('Clock type must be a ClockType enum')
        if clock_type == ClockType.UNINITIALIZED:
            raise ValueError('a clock needs a clock type')
        self._clock_type = clock_type
        # guards the jump handles and ROS time; waiters in sleep_until wait on it
        self._changed = threading.Condition()
        self._jump_handles: list[JumpHandle] = []

    @property
    def clock_type(self) -> ClockType:
        """Which time this clock reads."""
        return self._clock_type

    @property
    def ros_time_is_active(self) -> bool:
        """Only a ROSClock can follow ROS time."""
        return False

    def __repr__(self) -> str:
        return f'Clock(clock_type={self._clock_type.name})'

    def now(self) -> Time:
        """The clock's current time."""
        if self._clock_type == ClockType.STEADY_TIME:
            return Time(nanoseconds=time.monotonic_ns(), clock_type=self._clock_type)
        return Time(nanoseconds=time.time_ns(), clock_type=self._clock_type)

    # -- jump callbacks -----------------------------------------------------------------------
    def create_jump_callback(
        self,
        threshold: JumpThreshold,
        *,
        pre_callback: Callable[[], object] | None = None,
        post_callback: Callable[[TimeJump], object] | None = None,
    ) -> JumpHandle:
        """Call `pre_callback()` before and `post_callback(jump)` after each time jump that
        `threshold` selects, until the returned handle is unregistered."""
        handle = JumpHandle(self._remove_jump_handle, threshold, pre_callback, post_callback)
        with self._changed:
            self._jump_handles.append(handle)
        return handle

    def _remove_jump_handle(self, handle: JumpHandle) -> None:
        with self._changed:
            if handle in self._jump_handles:
                self._jump_handles.remove(handle)

    def _jump(self, jump: TimeJump, change: Callable[[], None]) -> None:
        """Make `change` with the selected callbacks around it, then wake sleepers."""
        with self._changed:
            handles = [h for h in self._jump_handles if h.threshold.exceeded(jump)]
        for handle in handles:
            if handle.pre_callback is not None:
                handle.pre_callback()
        with self._changed:
            change()
            self._changed.notify_all()
        for handle in handles:
            if handle.post_callback is not None:
                handle.post_callback(jump)

    # -- sleeping -----------------------------------------------------------------------------
    def sleep_until(self, until: Time, context: Context | None = None) -> bool:
        """Sleep until this clock reaches `until`. False when the context shut down or ROS
        time was switched on or off meanwhile (the target then means something else)."""
        ctx = context if context is not None else default_context()
        if not ctx.ok():
            raise NotInitializedException()
        if until.clock_type != self._clock_type:
            raise ValueError("until's clock type does not match this clock's type")
        wake = self._changed

        def on_shutdown() -> None:
            with wake:
                wake.notify_all()

        active = self.ros_time_is_active
        ctx.on_shutdown(on_shutdown)
        try:
            with wake:
                while True:
                    if not ctx.ok() or self.ros_time_is_active != active:
                        return False
                    left = until.nanoseconds - self.now().nanoseconds
                    if left <= 0:
                        return True
                    # under ROS time only a new time (or a switch) can end the wait
                    wake.wait(None if active else left / 1e9)
        finally:
            ctx.remove_on_shutdown(on_shutdown)

    def sleep_for(self, rel_time: Duration, context: Context | None = None) -> bool:
        """Sleep for `rel_time` of this clock (see :meth:`sleep_until`)."""
        return self.sleep_until(self.now() + rel_time, context)


class ROSClock(Clock):
    """ROS time: system time, or the time set from `/clock` while ROS time is active."""

    def __init__(self, *, clock_type: ClockType = ClockType.ROS_TIME) -> None:
        if clock_type != ClockType.ROS_TIME:
            raise ValueError('a ROSClock has clock type ROS_TIME')
        super().__init__(clock_type=ClockType.ROS_TIME)
        self._ros_time_active = False
        self._override_ns = 0

    def __new__(cls, *args: object, **kwargs: object) -> ROSClock:
        return object.__new__(cls)

    def __repr__(self) -> str:
        return f'ROSClock(ros_time_is_active={self._ros_time_active})'

    @property
    def ros_time_is_active(self) -> bool:
        """Whether the clock reads the time set from /clock rather than system time."""
        return self._ros_time_active

    def now(self) -> Time:
        """The override while ROS time is active, else system time."""
        if self._ros_time_active:
            return Time(nanoseconds=self._override_ns, clock_type=ClockType.ROS_TIME)
        return Time(nanoseconds=time.time_ns(), clock_type=ClockType.ROS_TIME)

    def set_ros_time_is_active(self, enabled: bool) -> None:
        """Switch between system time and the override (a time jump if it changes): the
        time source's switch."""
        if bool(enabled) == self._ros_time_active:
            return
        before = self.now().nanoseconds
        after = self._override_ns if enabled else time.time_ns()
        change = ClockChange.ROS_TIME_ACTIVATED if enabled else ClockChange.ROS_TIME_DEACTIVATED

        def switch() -> None:
            self._ros_time_active = bool(enabled)

        self._jump(TimeJump(change, Duration(nanoseconds=after - before)), switch)

    # rclpy's name, which rclpy code and tests call
    _set_ros_time_is_active = set_ros_time_is_active

    def set_ros_time_override(self, time_point: Time) -> None:
        """The time this clock reads while ROS time is active (a jump if it is active)."""
        if not isinstance(time_point, Time):
            raise TypeError('Time must be specified as rclpy.time.Time')
        new = time_point.nanoseconds

        def store() -> None:
            self._override_ns = new

        if not self._ros_time_active:
            with self._changed:
                store()
            return
        delta = Duration(nanoseconds=new - self._override_ns)
        self._jump(TimeJump(ClockChange.ROS_TIME_NO_CHANGE, delta), store)
