"""The diff-drive base: acceleration limits, timeouts, collisions, odometry."""

from __future__ import annotations

import math

import pytest

from ros2lite.sim.drive import Base, DriveLimits, Pose2D
from ros2lite.sim.world import Wall, WorldSpec, build_world

EMPTY = build_world(WorldSpec('empty', -10, -10, 10, 10, (), 0.1))


def _base(**kw: float) -> Base:
    limits = DriveLimits(0.16, 0.033, footprint_radius=0.105, **kw)
    return Base(limits, Pose2D(), seed=1)


def test_wheels_ramp_at_their_acceleration_limit() -> None:
    base = _base(wheel_accel=1.0, odom_noise=0.0)
    base.set_command(0.2, 0.0, 0.0)
    base.step(0.1, 0.1, EMPTY)
    assert base.linear == pytest.approx(0.1)
    base.step(0.1, 0.2, EMPTY)
    base.step(0.1, 0.3, EMPTY)
    assert base.linear == pytest.approx(0.2)


def test_odometry_without_noise_is_the_true_pose() -> None:
    base = _base(wheel_accel=0.0, odom_noise=0.0)
    base.set_command(0.2, 0.4, 0.0)
    for n in range(500):
        base.step(0.01, (n + 1) * 0.01, EMPTY)
    assert base.pose.yaw == pytest.approx(2.0)
    assert base.pose.x == pytest.approx(0.5 * math.sin(2.0), abs=1e-4)
    assert base.odom.x == pytest.approx(base.pose.x, abs=1e-9)
    assert base.odom.yaw == pytest.approx(base.pose.yaw, abs=1e-9)


def test_a_stale_command_stops_the_robot_when_a_timeout_is_set() -> None:
    base = _base(wheel_accel=0.0, cmd_timeout=0.5)
    base.set_command(0.2, 0.0, 0.0)
    base.step(0.01, 0.4, EMPTY)
    assert base.linear == pytest.approx(0.2)
    base.step(0.01, 0.6, EMPTY)
    assert base.linear == 0.0


def test_a_wall_stops_the_robot_once_and_it_can_back_away() -> None:
    world = build_world(WorldSpec('w', -2, -2, 2, 2, (Wall(0.5, -1, 0.5, 1, 0.1),), 0.02))
    base = _base(wheel_accel=0.0, odom_noise=0.0)
    base.set_command(0.2, 0.0, 0.0)
    contacts = [base.step(0.01, n * 0.01, world) for n in range(1, 400)]
    assert contacts.count(True) == 1
    assert base.pose.x == pytest.approx(0.45 - 0.105, abs=0.03)
    base.set_command(-0.2, 0.0, 4.0)
    base.step(0.1, 4.1, world)
    assert base.pose.x < 0.45 - 0.105 - 0.01
