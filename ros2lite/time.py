"""Points in time on a clock (rclpy.time's shape): `Time(seconds=…, nanoseconds=…,
clock_type=…)`, arithmetic with :class:`~ros2lite.duration.Duration`, and the
`builtin_interfaces/msg/Time` conversions.

Like rcl's time points, a Time is a non-negative signed 64-bit count of nanoseconds on one
clock type; comparing or subtracting times of different clock types is a TypeError, because
their numbers mean different things.
"""

from __future__ import annotations

import enum
from typing import TYPE_CHECKING, overload

from ros2lite.duration import Duration

if TYPE_CHECKING:
    from ros2lite.msgs.builtin_interfaces import msg as _builtin_msg

__all__ = ['ClockType', 'Time']

_NS = 1_000_000_000
_MAX_NS = 2**63 - 1


class ClockType(enum.IntEnum):
    """rcl's clock types (the numbers are rcl_clock_type_t's)."""

    UNINITIALIZED = 0
    ROS_TIME = 1
    SYSTEM_TIME = 2
    STEADY_TIME = 3


class Time:
    """A time point: nanoseconds since the clock's epoch, and which clock."""

    __slots__ = ('_clock_type', '_ns')

    def __init__(
        self,
        *,
        seconds: float = 0,
        nanoseconds: float = 0,
        clock_type: ClockType = ClockType.SYSTEM_TIME,
    ) -> None:
        if not isinstance(clock_type, ClockType):
            raise TypeError('Clock type must be a ClockType enum')
        if seconds < 0:
            raise ValueError('Seconds value must not be negative')
        if nanoseconds < 0:
            raise ValueError('Nanoseconds value must not be negative')
        total = int(seconds * _NS) + int(nanoseconds)
        if total > _MAX_NS:
            raise OverflowError('Total nanoseconds value is too large to store in a time point')
        self._ns = total
        self._clock_type = clock_type

    @property
    def nanoseconds(self) -> int:
        """Nanoseconds since the clock's epoch."""
        return self._ns

    @property
    def clock_type(self) -> ClockType:
        """The clock this time belongs to."""
        return self._clock_type

    def seconds_nanoseconds(self) -> tuple[int, int]:
        """(whole seconds, nanoseconds within the second), as builtin_interfaces has them."""
        sec, nsec = divmod(self._ns, _NS)
        return sec, nsec

    def __repr__(self) -> str:
        return f'Time(nanoseconds={self._ns}, clock_type={self._clock_type.name})'

    def __hash__(self) -> int:
        return hash((self._ns, self._clock_type))

    def __add__(self, other: Duration) -> Time:
        if not isinstance(other, Duration):
            return NotImplemented
        return Time(nanoseconds=self._ns + other.nanoseconds, clock_type=self._clock_type)

    __radd__ = __add__

    @overload
    def __sub__(self, other: Time) -> Duration: ...

    @overload
    def __sub__(self, other: Duration) -> Time: ...

    def __sub__(self, other: Time | Duration) -> Duration | Time:
        if isinstance(other, Time):
            self._same_clock(other)
            return Duration(nanoseconds=self._ns - other._ns)
        if isinstance(other, Duration):
            return Time(nanoseconds=self._ns - other.nanoseconds, clock_type=self._clock_type)
        return NotImplemented

    def _same_clock(self, other: Time) -> None:
        if self._clock_type != other._clock_type:
            raise TypeError("Can't compare or subtract times with different clock types")

    def _compare(self, other: object) -> int | None:
        if not isinstance(other, Time):
            return None
        self._same_clock(other)
        return (self._ns > other._ns) - (self._ns < other._ns)

    def __eq__(self, other: object) -> bool:
        order = self._compare(other)
        return order == 0 if order is not None else False

    def __ne__(self, other: object) -> bool:
        return not self == other

    def __lt__(self, other: Time) -> bool:
        order = self._compare(other)
        if order is None:
            return NotImplemented
        return order < 0

    def __le__(self, other: Time) -> bool:
        order = self._compare(other)
        if order is None:
            return NotImplemented
        return order <= 0

    def __gt__(self, other: Time) -> bool:
        order = self._compare(other)
        if order is None:
            return NotImplemented
        return order > 0

    def __ge__(self, other: Time) -> bool:
        order = self._compare(other)
        if order is None:
            return NotImplemented
        return order >= 0

    def to_msg(self) -> _builtin_msg.Time:
        """As a builtin_interfaces/msg/Time."""
        from ros2lite.interfaces import get_interface

        sec, nsec = self.seconds_nanoseconds()
        time_type: type[_builtin_msg.Time] = get_interface('builtin_interfaces/msg/Time')
        return time_type(sec=sec, nanosec=nsec)

    @classmethod
    def from_msg(cls, msg: _builtin_msg.Time, clock_type: ClockType = ClockType.ROS_TIME) -> Time:
        """From a `builtin_interfaces/msg/Time` (ROS time unless told otherwise)."""
        if not hasattr(msg, 'sec') or not hasattr(msg, 'nanosec'):
            raise TypeError('Must pass a builtin_interfaces.msg.Time object')
        return cls(seconds=msg.sec, nanoseconds=msg.nanosec, clock_type=clock_type)
