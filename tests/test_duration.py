"""The one Duration: rclpy's constructor, the rmw_time_t view, arithmetic and messages."""

from __future__ import annotations

import pytest

from ros2lite import Duration as PublicDuration
from ros2lite.clock import Duration as ClockDuration
from ros2lite.clock import Time
from ros2lite.duration import Duration
from ros2lite.interfaces import get_interface
from ros2lite.qos import DURATION_INFINITE, QoSProfile
from ros2lite.qos import Duration as QosDuration


def test_one_type_everywhere() -> None:
    assert PublicDuration is ClockDuration is QosDuration is Duration


def test_constructor_is_rclpy_shaped() -> None:
    assert Duration(seconds=1.5).nanoseconds == 1_500_000_000
    assert Duration(seconds=1, nanoseconds=5).nanoseconds == 1_000_000_005
    assert Duration().nanoseconds == 0 and Duration().is_unspecified
    assert Duration(seconds=0.1).nanoseconds == 100_000_000  # rounded, not truncated
    with pytest.raises(TypeError):
        Duration(5)  # type: ignore[misc]


def test_rmw_time_view() -> None:
    d = Duration(nanoseconds=2_000_000_001)
    assert (d.sec, d.nsec) == (2, 1)
    assert (DURATION_INFINITE.sec, DURATION_INFINITE.nsec) == (9223372036, 854775807)
    neg = Duration(nanoseconds=-1)
    assert (neg.sec, neg.nsec) == (-1, 999_999_999)  # floor, so sec * 1e9 + nsec holds


def test_arithmetic_order_and_hash() -> None:
    a, b = Duration(seconds=2), Duration(seconds=0.5)
    assert a - b == Duration(seconds=1.5) and a + b == Duration(seconds=2.5)
    assert -b == Duration(seconds=-0.5)
    assert b < a and a >= b and sorted([a, b]) == [b, a]
    assert len({Duration(seconds=1), Duration(nanoseconds=1_000_000_000)}) == 1
    assert Duration(seconds=1) != 1_000_000_000
    assert Time(nanoseconds=5_000_000_000) - Time(nanoseconds=1_000_000_000) == Duration(seconds=4)
    assert (Time(nanoseconds=5_000_000_000) + Duration(seconds=1)).nanoseconds == 6_000_000_000


def test_message_round_trip() -> None:
    msg = Duration(seconds=3, nanoseconds=7).to_msg()
    assert msg == get_interface('builtin_interfaces/msg/Duration')(sec=3, nanosec=7)
    assert Duration.from_msg(msg) == Duration(seconds=3, nanoseconds=7)


def test_qos_rejects_negative_durations() -> None:
    with pytest.raises(ValueError, match='lifespan must not be negative'):
        QoSProfile(depth=10, lifespan=Duration(seconds=-1))
