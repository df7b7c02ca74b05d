"""ROS time: Time, Duration and clocks, including `/clock` simulation time.

Kept rclpy-shaped (`node.get_clock().now().to_msg()`) because tutorial code relies on it.
"""

from __future__ import annotations

import enum
import threading
import time
from dataclasses import dataclass
from typing import TYPE_CHECKING, overload

from ros2lite.duration import Duration

if TYPE_CHECKING:
    from ros2lite.msgs.builtin_interfaces import msg as _builtin_msg

_NS = 1_000_000_000


class ClockType(enum.IntEnum):
    """Which time a clock tells (rcl's clock types)."""

    UNINITIALIZED = 0
    ROS_TIME = 1
    SYSTEM_TIME = 2
    STEADY_TIME = 3


@dataclass(frozen=True, order=True)
class Time:
    """A point in time (ns) on a clock type; rclpy's Time."""

    nanoseconds: int = 0
    clock_type: ClockType = ClockType.SYSTEM_TIME

    @classmethod
    def from_msg(cls, msg: _builtin_msg.Time, clock_type: ClockType = ClockType.ROS_TIME) -> Time:
        """From a builtin_interfaces/Time."""
        return cls(msg.sec * _NS + msg.nanosec, clock_type)

    @property
    def seconds_nanoseconds(self) -> tuple[int, int]:
        """(whole seconds, remaining nanoseconds)."""
        return divmod(self.nanoseconds, _NS)

    def to_msg(self) -> _builtin_msg.Time:
        """As a builtin_interfaces/Time."""
        from ros2lite.interfaces import get_interface

        sec, nsec = divmod(self.nanoseconds, _NS)
        time_type: type[_builtin_msg.Time] = get_interface('builtin_interfaces/msg/Time')
        return time_type(sec=sec, nanosec=nsec)

    @overload
    def __sub__(self, other: Time) -> Duration: ...

    @overload
    def __sub__(self, other: Duration) -> Time: ...

    def __sub__(self, other: Time | Duration) -> Duration | Time:
        if isinstance(other, Time):
            return Duration(nanoseconds=self.nanoseconds - other.nanoseconds)
        return Time(self.nanoseconds - other.nanoseconds, self.clock_type)

    def __add__(self, other: Duration) -> Time:
        return Time(self.nanoseconds + other.nanoseconds, self.clock_type)


class Clock:
    """System, steady or ROS time; ROS time follows `/clock` once sim time is enabled."""

    def __init__(self, clock_type: ClockType = ClockType.SYSTEM_TIME) -> None:
        self.clock_type = clock_type
        self._sim_ns: int | None = None  # None: ROS time is system time
        self._changed = threading.Condition()

    @property
    def ros_time_is_active(self) -> bool:
        """Whether ROS time follows /clock (use_sim_time)."""
        return self._sim_ns is not None

    def _enable_sim_time(self, enabled: bool) -> None:
        with self._changed:
            self._sim_ns = 0 if enabled else None
            self._changed.notify_all()

    def _set_sim_time(self, nanoseconds: int) -> None:
        with self._changed:
            if self._sim_ns is not None:
                self._sim_ns = nanoseconds
                self._changed.notify_all()

    def now(self) -> Time:
        """The clock's current time."""
        if self.clock_type == ClockType.STEADY_TIME:
            return Time(time.monotonic_ns(), self.clock_type)
        sim = self._sim_ns
        if sim is not None and self.clock_type == ClockType.ROS_TIME:
            return Time(sim, self.clock_type)
        return Time(time.time_ns(), self.clock_type)

    def sleep_for(self, duration: Duration | float) -> None:
        """Sleep for a duration of this clock's time (simulated time waits for /clock)."""
        seconds = duration.to_seconds() if isinstance(duration, Duration) else duration
        if self._sim_ns is None:
            time.sleep(max(0.0, seconds))
            return
        target = self.now().nanoseconds + round(seconds * _NS)
        with self._changed:
            while self._sim_ns is not None and self._sim_ns < target:
                self._changed.wait(0.1)
