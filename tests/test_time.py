"""rclpy's Time: keyword construction, the int64 range, clock types that must agree, and
arithmetic with Duration."""

from __future__ import annotations

import pytest

from ros2lite.duration import Duration, Infinite
from ros2lite.time import ClockType, Time


def test_construction_and_range() -> None:
    t = Time(seconds=1, nanoseconds=5e8, clock_type=ClockType.STEADY_TIME)
    assert (t.nanoseconds, t.clock_type) == (1_500_000_000, ClockType.STEADY_TIME)
    assert t.seconds_nanoseconds() == (1, 500_000_000)
    assert Time(nanoseconds=2**63 - 1).nanoseconds == 2**63 - 1
    with pytest.raises(OverflowError):
        Time(nanoseconds=2**63)
    with pytest.raises(ValueError):
        Time(seconds=-1)
    with pytest.raises(TypeError):
        Time(clock_type='SYSTEM_TIME')  # type: ignore[arg-type]


def test_arithmetic_and_comparison() -> None:
    one = Time(nanoseconds=1, clock_type=ClockType.ROS_TIME)
    later = Duration(nanoseconds=2) + one
    assert later == Time(nanoseconds=3, clock_type=ClockType.ROS_TIME)
    assert (later - one) == Duration(nanoseconds=2)
    with pytest.raises(ValueError):
        Time(nanoseconds=1) - Duration(nanoseconds=2)  # before the epoch
    with pytest.raises(OverflowError):
        Time(nanoseconds=2**63 - 1) + Duration(nanoseconds=1)
    with pytest.raises(TypeError):  # different clocks are different numbers
        _ = Time(nanoseconds=1) < Time(nanoseconds=2, clock_type=ClockType.STEADY_TIME)
    assert Time(nanoseconds=1) != Duration(nanoseconds=1)
    with pytest.raises(TypeError):
        _ = Duration(nanoseconds=1) < Time(nanoseconds=1)  # type: ignore[operator]


def test_messages_and_infinite() -> None:
    t = Time(nanoseconds=1_553_575_413_247_045_598, clock_type=ClockType.ROS_TIME)
    assert Time.from_msg(t.to_msg()) == t
    assert Time.from_msg(t.to_msg(), clock_type=ClockType.SYSTEM_TIME).clock_type == 2
    assert str(Infinite) == 'Infinite' and Infinite.nanoseconds == 2**63 - 1
    with pytest.raises(OverflowError):
        Duration(nanoseconds=-(2**63) - 1)
