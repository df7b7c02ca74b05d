"""TimeSource: a node's use_sim_time decides whether its ROS clocks read system time or the
latest `/clock`, and clocks attached later catch up."""

from __future__ import annotations

import time
from typing import Any

import pytest

from ros2lite.clock import Clock, ROSClock
from ros2lite.executors import SingleThreadedExecutor
from ros2lite.interfaces import get_interface
from ros2lite.node import Node
from ros2lite.parameter import Parameter
from ros2lite.time import ClockType, Time
from ros2lite.time_source import CLOCK_TOPIC, TimeSource
from tests.spinning import spin_for, spin_until

ClockMsg = get_interface('rosgraph_msgs/msg/Clock')


def test_attach_and_follow_use_sim_time(ros_context: Any) -> None:
    node = Node('sourced', context=ros_context)
    source = TimeSource(node=node)
    with pytest.raises(ValueError):
        source.attach_clock(Clock(clock_type=ClockType.SYSTEM_TIME))  # type: ignore[arg-type]
    clock = ROSClock()
    source.attach_clock(clock)
    assert not source.ros_time_is_active and source._clock_sub is None
    assert abs(clock.now().nanoseconds - time.time_ns()) < 1e9
    assert node.set_parameters([Parameter('use_sim_time', value=True)])[0].successful
    assert source.ros_time_is_active and clock.ros_time_is_active
    assert clock.now() == Time(clock_type=ClockType.ROS_TIME)  # no /clock yet
    refused = node.set_parameters([Parameter('use_sim_time', value='yes')])[0]
    assert not refused.successful

    pub = Node('clock_source', context=ros_context).create_publisher(ClockMsg, CLOCK_TOPIC, 10)
    ex = SingleThreadedExecutor(context=ros_context)
    ex.add_node(node)

    def ticked() -> bool:
        pub.publish(ClockMsg(clock=Time(seconds=42).to_msg()))
        spin_for(ex, 0.02)
        return clock.now().nanoseconds == 42_000_000_000

    spin_until(ex, ticked)
    late = ROSClock()
    source.attach_clock(late)  # the newest /clock time, at once
    assert late.ros_time_is_active and late.now().nanoseconds == 42_000_000_000
    source.detach_node()
    assert source._clock_sub is None and source._get_node() is None
