"""A differential-drive base: commanded twist → wheel speeds (limited) → the true pose, and
the wheel odometry a robot would integrate from its encoders (with noise, so it drifts).

Limits follow Gazebo's diff-drive plugins: each wheel's linear speed changes by at most
`wheel_accel` m/s² (gazebo_ros_diff_drive's max_wheel_acceleration); optional caps on the
body's speeds; a command older than `cmd_timeout` seconds (0: never) stops the robot, as
ros2_control's diff_drive_controller does. A move that would put the robot's footprint into
an obstacle is not made: the robot stops there, and `collided` says so.
"""

from __future__ import annotations

import math
import random
from dataclasses import dataclass

from ros2lite.sim.world import Grid

__all__ = ['Base', 'DriveLimits', 'Pose2D']


@dataclass
class Pose2D:
    """A planar pose: metres and radians."""

    x: float = 0.0
    y: float = 0.0
    yaw: float = 0.0


@dataclass(frozen=True)
class DriveLimits:
    """The base's geometry and limits (0 = no limit)."""

    wheel_separation: float
    wheel_radius: float
    footprint_radius: float
    wheel_accel: float = 1.0
    max_linear: float = 0.0
    max_angular: float = 0.0
    cmd_timeout: float = 0.0
    # stddev of each wheel's measured travel, as a fraction of that travel
    odom_noise: float = 0.005


class Base:
    """One robot base in a world: command in, step, read pose, speeds, wheels and odometry."""

    def __init__(self, limits: DriveLimits, start: Pose2D, seed: int | None = None) -> None:
        self.limits = limits
        self.start = Pose2D(start.x, start.y, start.yaw)
        self.random = random.Random(seed)
        self.reset()

    def reset(self, start: Pose2D | None = None) -> None:
        """Back to the start pose (or `start`), at rest, odometry at zero."""
        if start is not None:
            self.start = Pose2D(start.x, start.y, start.yaw)
        self.pose = Pose2D(self.start.x, self.start.y, self.start.yaw)
        self.odom = Pose2D()
        self.wheel_speed = [0.0, 0.0]  # left, right: m/s at the rim
        self.wheel_angle = [0.0, 0.0]
        self.linear = 0.0  # true body speeds after the last step
        self.angular = 0.0
        self.odom_linear = 0.0
        self.odom_angular = 0.0
        self.command = (0.0, 0.0)
        self.command_time = -math.inf
        self.collided = False

    def set_command(self, linear: float, angular: float, now: float) -> None:
        """A new twist (m/s forward, rad/s about z) at sim time `now`."""
        lim = self.limits
        if lim.max_linear > 0:
            linear = max(-lim.max_linear, min(lim.max_linear, linear))
        if lim.max_angular > 0:
            angular = max(-lim.max_angular, min(lim.max_angular, angular))
        self.command = (linear, angular)
        self.command_time = now

    def step(self, dt: float, now: float, world: Grid) -> bool:
        """Advance `dt` seconds; True when this step ran into an obstacle (first contact)."""
        lim = self.limits
        linear, angular = self.command
        if lim.cmd_timeout > 0 and now - self.command_time > lim.cmd_timeout:
            linear = angular = 0.0
        half = lim.wheel_separation / 2
        wanted = (linear - angular * half, linear + angular * half)
        for side in (0, 1):
            change = wanted[side] - self.wheel_speed[side]
            bound = lim.wheel_accel * dt
            if lim.wheel_accel > 0 and abs(change) > bound:
                change = math.copysign(bound, change)
            self.wheel_speed[side] += change
        left, right = self.wheel_speed
        v = (left + right) / 2
        w = (right - left) / lim.wheel_separation
        pose = self.pose
        yaw = pose.yaw + w * dt / 2
        nx = pose.x + v * dt * math.cos(yaw)
        ny = pose.y + v * dt * math.sin(yaw)
        first_contact = False
        room = world.clearance(nx, ny) if v != 0.0 else math.inf
        if room < lim.footprint_radius and room <= world.clearance(pose.x, pose.y):
            # blocked (moving in, not away): the wheels stall, turning in place stays allowed
            first_contact = not self.collided
            self.collided = True
            self.wheel_speed = [-w * half, w * half]
            v = 0.0
            nx, ny = pose.x, pose.y
        elif v != 0.0:
            self.collided = False
        pose.x, pose.y = nx, ny
        pose.yaw = _wrap(pose.yaw + w * dt)
        self.linear, self.angular = v, w
        self._odometry(v - w * half, v + w * half, dt)
        return first_contact

    def _odometry(self, left: float, right: float, dt: float) -> None:
        """Integrate the wheels' measured travel (true travel, plus noise) into `odom`."""
        lim = self.limits
        travel = [left * dt, right * dt]
        for side in (0, 1):
            self.wheel_angle[side] += travel[side] / lim.wheel_radius
            if lim.odom_noise > 0 and travel[side] != 0.0:
                travel[side] += self.random.gauss(0.0, lim.odom_noise * abs(travel[side]))
        ds = (travel[0] + travel[1]) / 2
        dyaw = (travel[1] - travel[0]) / lim.wheel_separation
        odom = self.odom
        mid = odom.yaw + dyaw / 2
        odom.x += ds * math.cos(mid)
        odom.y += ds * math.sin(mid)
        odom.yaw = _wrap(odom.yaw + dyaw)
        self.odom_linear = ds / dt if dt > 0 else 0.0
        self.odom_angular = dyaw / dt if dt > 0 else 0.0


def _wrap(angle: float) -> float:
    return math.atan2(math.sin(angle), math.cos(angle))
