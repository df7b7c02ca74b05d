"""Time, Duration and clocks; simulation time driven by `/clock` (`use_sim_time`)."""

from __future__ import annotations

import time
from typing import Any

import pytest

from ros2lite.clock import Clock, ClockType, Duration, ROSClock, Time
from ros2lite.executors import SingleThreadedExecutor
from ros2lite.interfaces import get_interface
from ros2lite.node import Node
from ros2lite.parameter import Parameter
from tests.spinning import spin_for, spin_until

ClockMsg = get_interface('rosgraph_msgs/msg/Clock')
TimeMsg = get_interface('builtin_interfaces/msg/Time')


def test_time_and_duration_arithmetic() -> None:
    t = Time(nanoseconds=5_500_000_000)
    assert t.seconds_nanoseconds() == (5, 500_000_000)
    assert (t + Duration.from_seconds(0.5)).nanoseconds == 6_000_000_000
    assert t - Time(nanoseconds=1_000_000_000) == Duration(nanoseconds=4_500_000_000)
    assert (t - Duration(nanoseconds=500_000_000)).nanoseconds == 5_000_000_000
    assert Duration.from_seconds(1.25).to_seconds() == 1.25
    msg = t.to_msg()
    assert (msg.sec, msg.nanosec) == (5, 500_000_000)
    assert Time.from_msg(msg) == Time(nanoseconds=5_500_000_000, clock_type=ClockType.ROS_TIME)
    d = Duration(nanoseconds=2_000_000_001).to_msg()
    assert (d.sec, d.nanosec) == (2, 1)
    assert Time(nanoseconds=1) < Time(nanoseconds=2)


def test_clock_types() -> None:
    system = Clock(clock_type=ClockType.SYSTEM_TIME).now().nanoseconds
    assert abs(system - time.time_ns()) < 1_000_000_000
    steady = Clock(clock_type=ClockType.STEADY_TIME).now()
    assert steady.clock_type == ClockType.STEADY_TIME
    assert abs(steady.nanoseconds - time.monotonic_ns()) < 1_000_000_000
    ros = Clock(clock_type=ClockType.ROS_TIME)
    assert not ros.ros_time_is_active
    assert abs(ros.now().nanoseconds - time.time_ns()) < 1_000_000_000


def publish_clock(pub: Any, ns: int) -> None:
    pub.publish(ClockMsg(clock=TimeMsg(sec=ns // 1_000_000_000, nanosec=ns % 1_000_000_000)))


@pytest.fixture
def clock_pub(ros_context: Any) -> Any:
    source = Node('sim_source', context=ros_context, enable_rosout=False)
    return source.create_publisher(ClockMsg, '/clock', 10)


def test_sim_time_follows_clock_topic(ros_context: Any, clock_pub: Any) -> None:
    node = Node(
        'simulated', context=ros_context, cli_args=['--ros-args', '-p', 'use_sim_time:=true']
    )
    assert node.get_parameter('use_sim_time').value is True
    clock = node.get_clock()
    assert clock.ros_time_is_active
    assert clock.now().nanoseconds == 0  # no /clock yet
    ex = SingleThreadedExecutor(context=ros_context)
    ex.add_node(node)
    target = 42 * 1_000_000_000 + 5

    def sent_and_seen() -> bool:
        publish_clock(clock_pub, target)  # repeat: the first may precede discovery
        spin_for(ex, 0.02)
        return clock.now().nanoseconds == target

    spin_until(ex, sent_and_seen)
    assert clock.now() == Time(nanoseconds=target, clock_type=ClockType.ROS_TIME)
    # switching sim time off goes back to the system clock
    node.set_parameters([Parameter('use_sim_time', value=False)])
    assert not clock.ros_time_is_active
    assert abs(clock.now().nanoseconds - time.time_ns()) < 1_000_000_000


def test_timers_follow_sim_time(ros_context: Any, clock_pub: Any) -> None:
    node = Node(
        'sim_timer',
        context=ros_context,
        parameter_overrides=[Parameter('use_sim_time', value=True)],
    )
    calls: list[int] = []
    node.create_timer(1.0, lambda: calls.append(node.get_clock().now().nanoseconds))
    ex = SingleThreadedExecutor(context=ros_context)
    ex.add_node(node)
    spin_for(ex, 1.2)  # a second of wall time is nothing in sim time
    assert calls == []

    def advanced() -> bool:
        publish_clock(clock_pub, 1_500_000_000)
        spin_for(ex, 0.02)
        return bool(calls)

    spin_until(ex, advanced)
    assert calls[0] == 1_500_000_000


def test_sim_time_enabled_later(ros_context: Any, clock_pub: Any) -> None:
    node = Node('late_sim', context=ros_context)
    assert not node.get_clock().ros_time_is_active
    node.set_parameters([Parameter('use_sim_time', value=True)])
    ex = SingleThreadedExecutor(context=ros_context)
    ex.add_node(node)

    def seen() -> bool:
        publish_clock(clock_pub, 7_000_000_000)
        spin_for(ex, 0.02)
        return node.get_clock().now().nanoseconds == 7_000_000_000

    spin_until(ex, seen)


def test_sleep_for_under_sim_time(ros_context: Any) -> None:
    clock = ROSClock()
    clock._set_ros_time_is_active(True)
    clock.set_ros_time_override(Time(seconds=1, clock_type=ClockType.ROS_TIME))
    import threading

    later = Time(seconds=3, clock_type=ClockType.ROS_TIME)
    threading.Timer(0.1, clock.set_ros_time_override, args=(later,)).start()
    start = time.monotonic()
    assert clock.sleep_for(Duration.from_seconds(1.5), context=ros_context)
    assert 0.05 < time.monotonic() - start < 1.0
    assert clock.now().nanoseconds == 3_000_000_000


def test_clock_types_and_ros_clock() -> None:
    from ros2lite.clock import ROSClock

    assert isinstance(Clock(clock_type=ClockType.ROS_TIME), ROSClock)
    assert not Clock(clock_type=ClockType.STEADY_TIME).ros_time_is_active
    with pytest.raises(TypeError):
        Clock(clock_type='STEADY_TIME')  # type: ignore[arg-type]


def test_jump_callbacks_follow_their_thresholds() -> None:
    from ros2lite.clock import ClockChange, JumpThreshold, ROSClock

    with pytest.raises(ValueError, match='min_forward'):
        JumpThreshold(min_forward=Duration(), min_backward=None)
    with pytest.raises(ValueError, match='must be enabled'):
        JumpThreshold(min_forward=None, min_backward=None, on_clock_change=False)
    clock = ROSClock()
    forward: list[Any] = []
    changes: list[Any] = []
    pre: list[int] = []
    jump = JumpThreshold(min_forward=Duration(seconds=1), min_backward=None, on_clock_change=False)
    handle = clock.create_jump_callback(
        jump, pre_callback=lambda: pre.append(1), post_callback=forward.append
    )
    with clock.create_jump_callback(
        JumpThreshold(min_forward=None, min_backward=None), post_callback=changes.append
    ):
        clock.set_ros_time_override(Time(seconds=10, clock_type=ClockType.ROS_TIME))
        assert forward == []  # ROS time is not active yet: no jump
        clock._set_ros_time_is_active(True)
        assert [c.clock_change for c in changes] == [ClockChange.ROS_TIME_ACTIVATED]
    clock.set_ros_time_override(Time(seconds=10.5, clock_type=ClockType.ROS_TIME))
    assert forward == []  # below the threshold
    clock.set_ros_time_override(Time(seconds=12, clock_type=ClockType.ROS_TIME))
    assert [j.delta for j in forward] == [Duration(seconds=1.5)] and pre == [1]
    handle.unregister()
    clock._set_ros_time_is_active(False)  # the `with` handle is gone too
    assert len(changes) == 1


def test_sleep_ends_false_when_the_context_shuts_down(ros_router: str) -> None:
    from ros2lite.context import Context
    from ros2lite.exceptions import NotInitializedException

    clock = Clock()
    with pytest.raises(NotInitializedException):
        clock.sleep_for(Duration(nanoseconds=10_000_000), context=Context())
    ctx = Context().init([])
    result: list[bool] = []
    import threading

    sleeper = threading.Thread(
        target=lambda: result.append(clock.sleep_for(Duration(seconds=30), context=ctx))
    )
    sleeper.start()
    time.sleep(0.1)
    ctx.shutdown()
    sleeper.join(5)
    assert result == [False]
