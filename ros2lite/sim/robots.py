"""The courses' robots by the names they are launched with: what each one's Gazebo
simulation advertises (topics, types, rates, frames) and its body (dimensions, frames).

One spec per robot is the one place these facts live: the node publishes from it and
`urdf()` writes the robot's description from it (our own text: the same frame names and
dimensions as the robot's, nothing copied). Facts, from the robots' Gazebo model files:

- TurtleBot3 (turtlebot3_gazebo's burger/waffle SDF): LDS laser 360 beams over 0..6.28 rad,
  0.12-3.5 m, 5 Hz, noise 0.01 m, frame `base_scan`, topic `scan` (gazebo_ros_ray_sensor:
  sensor-data QoS, best effort); diff drive at 30 Hz, `odom` → `base_footprint`, wheel
  separation 0.160 (burger) / 0.287 (waffle), wheel radius 0.033, max wheel acceleration 1.0;
  joint states at 30 Hz; IMU `imu` at 200 Hz on `imu_link`; the waffle's camera `camera`
  (`/camera/image_raw`, `/camera/camera_info`, frame `camera_rgb_frame`, hfov 1.02974 rad,
  30 Hz; Gazebo renders 1920x1080, we draw a smaller picture of the same aspect).
  Jazzy's gz bridge takes `cmd_vel` as TwistStamped, Humble's gazebo_ros_diff_drive as Twist:
  the node listens to both.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from ros2lite.sim.drive import DriveLimits, Pose2D
from ros2lite.sim.errors import SimError
from ros2lite.sim.sensors import CameraSpec, ImuSpec, LaserSpec

__all__ = ['ROBOTS', 'Joint', 'RobotSpec', 'robot', 'urdf']

Xyz = tuple[float, float, float]


@dataclass(frozen=True)
class Joint:
    """A joint of the description: fixed, or a continuous wheel turning about its y axis."""

    name: str
    parent: str
    child: str
    xyz: Xyz
    rpy: Xyz = (0.0, 0.0, 0.0)
    kind: str = 'fixed'
    # a box (x, y, z sizes) or cylinder (radius, length, 0) drawn for the child link
    shape: tuple[str, Xyz] | None = None


@dataclass(frozen=True)
class RobotSpec:
    """One simulated robot: its drive, sensors, topics, rates and frames."""

    name: str
    banner: str
    limits: DriveLimits
    start: Pose2D
    joints: tuple[Joint, ...]
    laser: LaserSpec
    imu: ImuSpec | None = None
    camera: CameraSpec | None = None
    cmd_vel: str = 'cmd_vel'
    # a twist multiplexer's inputs, (topic, priority, timeout s), when the robot has one
    # (the highest-priority input heard within its timeout drives); empty: `cmd_vel` alone
    twist_mux: tuple[tuple[str, int, float], ...] = ()
    odom_topic: str = 'odom'
    # more topics carrying the same odometry (a localisation filter's output, as the real
    # robot's launch has one), and more carrying the IMU's readings
    odom_copies: tuple[str, ...] = ()
    imu_copies: tuple[str, ...] = ()
    odom_frame: str = 'odom'
    base_frame: str = 'base_footprint'
    odom_rate: float = 30.0
    publish_odom_tf: bool = True
    joint_states_rate: float = 30.0
    wheel_joints: tuple[str, ...] = ('wheel_left_joint', 'wheel_right_joint')
    body_rgb: tuple[float, float, float] = (0.3, 0.3, 0.3)
    extra: dict[str, str] = field(default_factory=dict)


def _wheel(name: str, parent: str, child: str, xyz: Xyz, shape: tuple[str, Xyz]) -> Joint:
    """A drive wheel: a continuous joint turned so the wheel spins about the body's y axis."""
    return Joint(name, parent, child, xyz, (-math.pi / 2, 0.0, 0.0), 'continuous', shape)


def _banner(robot: str) -> str:
    """The line the simulator logs when it starts `robot` (a model's name as people say it)."""
    return (
        f"ros2lite's 2D stand-in for the Gazebo simulation of {robot} "
        '(a flat world: no physics engine, same topics, frames and rates)'
    )


def _tb3_joints(separation: float, laser_x: float, laser_z: float, waffle: bool) -> list[Joint]:
    half = separation / 2
    wheel = ('cylinder', (0.033, 0.018, 0.0))
    joints = [
        Joint('base_joint', 'base_footprint', 'base_link', (0.0, 0.0, 0.010)),
        _wheel('wheel_left_joint', 'base_link', 'wheel_left_link', (0.0, half, 0.023), wheel),
        _wheel('wheel_right_joint', 'base_link', 'wheel_right_link', (0.0, -half, 0.023), wheel),
        Joint('imu_joint', 'base_link', 'imu_link', (-0.032, 0.0, 0.068)),
        Joint(
            'scan_joint',
            'base_link',
            'base_scan',
            (laser_x, 0.0, laser_z),
            shape=('cylinder', (0.0508, 0.055, 0.0)),
        ),
    ]
    if waffle:
        joints += [
            Joint(
                'caster_back_right_joint',
                'base_link',
                'caster_back_right_link',
                (-0.177, -0.064, -0.004),
                (-math.pi / 2, 0.0, 0.0),
            ),
            Joint(
                'caster_back_left_joint',
                'base_link',
                'caster_back_left_link',
                (-0.177, 0.064, -0.004),
                (-math.pi / 2, 0.0, 0.0),
            ),
            Joint('camera_joint', 'base_link', 'camera_link', (0.064, -0.065, 0.094)),
            Joint('camera_rgb_joint', 'camera_link', 'camera_rgb_frame', (0.005, 0.018, 0.013)),
            Joint(
                'camera_rgb_optical_joint',
                'camera_rgb_frame',
                'camera_rgb_optical_frame',
                (0.0, 0.0, 0.0),
                (-math.pi / 2, 0.0, -math.pi / 2),
            ),
        ]
    else:
        joints.append(
            Joint(
                'caster_back_joint',
                'base_link',
                'caster_back_link',
                (-0.081, 0.0, -0.004),
                (-math.pi / 2, 0.0, 0.0),
            )
        )
    return joints


def _tb3_laser(x: float) -> LaserSpec:
    return LaserSpec(
        topic='scan',
        frame_id='base_scan',
        samples=360,
        angle_min=0.0,
        angle_max=6.28,
        range_min=0.12,
        range_max=3.5,
        rate=5.0,
        noise=0.01,
        x=x,
    )


_TB3_IMU = ImuSpec('imu', 'imu_link', 200.0, gyro_noise=2e-4, accel_noise=1.7e-2)

ROBOTS: dict[str, RobotSpec] = {
    'burger': RobotSpec(
        name='burger',
        banner=_banner('TurtleBot3 burger'),
        limits=DriveLimits(0.160, 0.033, footprint_radius=0.105, wheel_accel=1.0),
        start=Pose2D(-2.0, -0.5, 0.0),
        joints=tuple(_tb3_joints(0.160, -0.032, 0.172, waffle=False)),
        laser=_tb3_laser(-0.032),
        imu=_TB3_IMU,
        body_rgb=(0.2, 0.2, 0.2),
    ),
    'waffle': RobotSpec(
        name='waffle',
        banner=_banner('TurtleBot3 waffle'),
        limits=DriveLimits(0.287, 0.033, footprint_radius=0.2, wheel_accel=1.0),
        start=Pose2D(-2.0, -0.5, 0.0),
        joints=tuple(_tb3_joints(0.287, -0.064, 0.122, waffle=True)),
        laser=_tb3_laser(-0.064),
        imu=_TB3_IMU,
        camera=CameraSpec(
            image_topic='camera/image_raw',
            info_topic='camera/camera_info',
            frame_id='camera_rgb_frame',
            width=320,
            height=180,
            hfov=1.02974,
            rate=30.0,
            x=0.069,
            y=-0.047,
            z=0.117,
        ),
        body_rgb=(0.3, 0.3, 0.3),
    ),
}
ROBOTS['waffle_pi'] = ROBOTS['waffle']

# Clearpath Jackal (jackal_description foxy-devel, jackal_control's control.yaml): the front
# laser is the default Hokuyo UST-10 (720 beams over ±2.35619 rad, 0.1-30 m, 50 Hz, noise
# 0.001 m) on `front/scan`, frame `front_laser`; diff_drive_controller at 50 Hz with a 0.25 s
# cmd_vel timeout, odom -> base_link (the EKF's /odometry/filtered and its TF; the
# controller's odometry on /odom as the courses see it); IMU `imu/data_raw` at 100 Hz
# (and the Madgwick filter's `imu/data`).
_JACKAL_WHEEL = ('cylinder', (0.098, 0.04, 0.0))
ROBOTS['jackal'] = RobotSpec(
    name='jackal',
    banner=_banner('Clearpath Jackal'),
    limits=DriveLimits(
        0.37559,
        0.098,
        footprint_radius=0.3,
        wheel_accel=20.0,
        max_linear=2.0,
        max_angular=4.0,
        cmd_timeout=0.25,
    ),
    start=Pose2D(0.0, 0.0, 0.0),
    joints=(
        Joint(
            'base_link_joint',
            'base_link',
            'chassis_link',
            (0.0, 0.0, 0.0),
            shape=('box', (0.42, 0.31, 0.184)),
        ),
        *(
            _wheel(
                f'{end}_{side}_wheel_joint',
                'chassis_link',
                f'{end}_{side}_wheel_link',
                (x, y, 0.0345),
                _JACKAL_WHEEL,
            )
            for end, x in (('front', 0.131), ('rear', -0.131))
            for side, y in (('left', 0.187795), ('right', -0.187795))
        ),
        Joint('imu_joint', 'chassis_link', 'imu_link', (0.0, 0.0, 0.0)),
        Joint('front_mount_joint', 'chassis_link', 'front_mount', (0.12, 0.0, 0.184)),
        Joint('front_laser_mount_joint', 'front_mount', 'front_laser_mount', (0.0, 0.0, 0.0)),
        Joint(
            'front_laser_joint',
            'front_laser_mount',
            'front_laser',
            (0.0, 0.0, 0.0474),
            shape=('cylinder', (0.025, 0.07, 0.0)),
        ),
    ),
    laser=LaserSpec(
        topic='front/scan',
        frame_id='front_laser',
        samples=720,
        angle_min=-2.35619,
        angle_max=2.35619,
        range_min=0.1,
        range_max=30.0,
        rate=50.0,
        noise=0.001,
        x=0.12,
    ),
    imu=ImuSpec('imu/data_raw', 'imu_link', 100.0, gyro_noise=0.005, accel_noise=0.005),
    odom_topic='odom',
    odom_copies=('odometry/filtered',),
    imu_copies=('imu/data',),
    base_frame='base_link',
    odom_rate=50.0,
    joint_states_rate=50.0,
    wheel_joints=(
        'front_left_wheel_joint',
        'front_right_wheel_joint',
        'rear_left_wheel_joint',
        'rear_right_wheel_joint',
    ),
    body_rgb=(0.1, 0.1, 0.1),
)


# PAL TIAGo's base (pmb2_description, pmb2_controller_configuration): the SICK TiM571 on
# `scan_raw` (220 degrees, 666 beams, 0.05-25 m, 10 Hz, noise 0.06 m) in base_laser_link,
# 0.202 m ahead; mobile_base_controller at 50 Hz (wheel separation 0.4044, radius 0.0985,
# 1 m/s, 1.05 rad/s, 0.25 s timeout), odometry on mobile_base_controller/odom, odom ->
# base_footprint; the head's Xtion on head_front_camera/rgb/image_raw; the twist mux of
# tiago_bringup (joystick, tablet, marker, keyboard key_vel, navigation nav_vel).
_TIAGO_WHEEL = ('cylinder', (0.0985, 0.04, 0.0))
ROBOTS['tiago'] = RobotSpec(
    name='tiago',
    banner=_banner('PAL TIAGo'),
    limits=DriveLimits(
        0.4044,
        0.0985,
        footprint_radius=0.27,
        wheel_accel=0.5,
        max_linear=1.0,
        max_angular=1.05,
        cmd_timeout=0.25,
    ),
    start=Pose2D(0.0, 0.0, 0.0),
    joints=(
        Joint(
            'base_footprint_joint',
            'base_footprint',
            'base_link',
            (0.0, 0.0, 0.0762),
            shape=('cylinder', (0.27, 0.3, 0.0)),
        ),
        _wheel(
            'wheel_left_joint', 'base_link', 'wheel_left_link', (0.0, 0.2022, -0.0762), _TIAGO_WHEEL
        ),
        _wheel(
            'wheel_right_joint',
            'base_link',
            'wheel_right_link',
            (0.0, -0.2022, -0.0762),
            _TIAGO_WHEEL,
        ),
        Joint('base_laser_joint', 'base_link', 'base_laser_link', (0.202, 0.0, -0.004)),
        Joint('base_imu_joint', 'base_link', 'base_imu_link', (0.1044, 0.0, 0.0)),
        Joint(
            'torso_fixed_joint',
            'base_link',
            'torso_fixed_link',
            (-0.062, 0.0, 0.193),
            shape=('box', (0.25, 0.3, 0.6)),
        ),
        Joint(
            'head_front_camera_joint',
            'torso_fixed_link',
            'head_front_camera_link',
            (0.11, 0.0, 0.85),
        ),
        Joint(
            'head_front_camera_rgb_optical_joint',
            'head_front_camera_link',
            'head_front_camera_rgb_optical_frame',
            (0.0, 0.0, 0.0),
            (-math.pi / 2, 0.0, -math.pi / 2),
        ),
    ),
    laser=LaserSpec(
        topic='scan_raw',
        frame_id='base_laser_link',
        samples=666,
        angle_min=-1.91986,
        angle_max=1.91986,
        range_min=0.05,
        range_max=25.0,
        rate=10.0,
        noise=0.06,
        x=0.202,
    ),
    imu=ImuSpec('base_imu', 'base_imu_link', 100.0, gyro_noise=0.001, accel_noise=0.01),
    camera=CameraSpec(
        image_topic='head_front_camera/rgb/image_raw',
        info_topic='head_front_camera/rgb/camera_info',
        frame_id='head_front_camera_rgb_optical_frame',
        width=320,
        height=240,
        hfov=1.0472,
        rate=30.0,
        x=0.048,
        z=1.12,
    ),
    odom_topic='mobile_base_controller/odom',
    odom_rate=50.0,
    joint_states_rate=50.0,
    twist_mux=(
        ('joy_vel', 100, 0.5),
        ('tab_vel', 100, 0.5),
        ('marker_vel', 98, 0.5),
        ('key_vel', 90, 0.5),
        ('nav_vel', 10, 0.5),
    ),
    body_rgb=(0.85, 0.85, 0.85),
)


def robot(name: str) -> RobotSpec:
    """The spec of robot `name` (a TURTLEBOT3_MODEL value or another robot's name)."""
    try:
        return ROBOTS[name]
    except KeyError:
        known = ', '.join(sorted(ROBOTS))
        raise SimError(f'unknown robot model {name!r} (known: {known})') from None


def urdf(spec: RobotSpec) -> str:
    """The robot's description as URDF text, written from its spec."""
    links = [spec.base_frame] + [j.child for j in spec.joints]
    shapes = {j.child: j.shape for j in spec.joints if j.shape}
    radius = spec.limits.footprint_radius
    body = ('cylinder', (radius, 0.14, 0.0))
    lines = ['<?xml version="1.0"?>', f'<robot name="{spec.name}">']
    r, g, b = spec.body_rgb
    lines.append(f'  <material name="body"><color rgba="{r} {g} {b} 1"/></material>')
    for link in links:
        shape = body if link == 'base_link' else shapes.get(link)
        if shape is None:
            lines.append(f'  <link name="{link}"/>')
            continue
        kind, (a, c, d) = shape
        geometry = (
            f'<box size="{a} {c} {d}"/>'
            if kind == 'box'
            else f'<cylinder radius="{a}" length="{c}"/>'
        )
        z = c / 2 if link == 'base_link' else 0.0
        lines += [
            f'  <link name="{link}">',
            f'    <visual><origin xyz="0 0 {z}"/><geometry>{geometry}</geometry>'
            '<material name="body"/></visual>',
            f'    <collision><origin xyz="0 0 {z}"/><geometry>{geometry}</geometry></collision>',
            '  </link>',
        ]
    for j in spec.joints:
        x, y, z = j.xyz
        rr, pp, yy = j.rpy
        lines.append(f'  <joint name="{j.name}" type="{j.kind}">')
        lines.append(f'    <parent link="{j.parent}"/><child link="{j.child}"/>')
        lines.append(f'    <origin xyz="{x} {y} {z}" rpy="{rr} {pp} {yy}"/>')
        if j.kind != 'fixed':
            lines.append('    <axis xyz="0 0 1"/>')
        lines.append('  </joint>')
    lines.append('</robot>')
    return '\n'.join(lines) + '\n'
