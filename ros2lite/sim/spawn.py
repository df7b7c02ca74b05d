"""A workspace's own robot for the 2D world: its URDF's Gazebo plugin tags read into a spec.

What the simulator needs is what Gazebo's plugins are told: the diff-drive plugin
(gazebo_ros_diff_drive or gz-sim's DiffDrive: wheel separation and size, command and odometry
topics, frames, rate, acceleration) and each ray sensor (`ray`, `gpu_ray`, `lidar`,
`gpu_lidar`: beams, angles, range, noise, rate, topic, frame), placed where the URDF's
joints put its link. The footprint is the base link's collision geometry.

A robot joins a running world as a `SpawnRequest` published (std_msgs/String, JSON) on
`SPAWN_TOPIC`; the world answers on `SPAWNED_TOPIC` with the request's id. ros2lite's bundled
interfaces have neither gazebo_msgs' SpawnEntity nor ros_gz_interfaces' SpawnEntity, and a
topic of strings needs no new interface: the spawners speak it, users run the spawners.
"""

from __future__ import annotations

import json
import math
import uuid
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field

from ros2lite.exceptions import NameValidationException
from ros2lite.names import validate_namespace
from ros2lite.sim.drive import DriveLimits, Pose2D
from ros2lite.sim.errors import SimError
from ros2lite.sim.robots import Joint, RobotSpec
from ros2lite.sim.sensors import LaserSpec
from ros2lite.urdf import Robot, UrdfError, parse_urdf

__all__ = ['SPAWNED_TOPIC', 'SPAWN_TOPIC', 'SpawnRequest', 'spec_from_urdf']

SPAWN_TOPIC = '/gazebo/spawn_2d'
SPAWNED_TOPIC = '/gazebo/spawned_2d'


@dataclass(frozen=True)
class SpawnRequest:
    """One robot to add: its name, its URDF (after xacro), where, and its topics' namespace."""

    name: str
    urdf: str
    x: float = 0.0
    y: float = 0.0
    yaw: float = 0.0
    namespace: str = ''
    id: str = field(default_factory=lambda: uuid.uuid4().hex)

    def to_json(self) -> str:
        return json.dumps(self.__dict__)

    @classmethod
    def from_json(cls, text: str) -> SpawnRequest:
        """The request a spawner sent; a malformed one is a SimError."""
        try:
            data = json.loads(text)
            request = cls(
                name=str(data['name']),
                urdf=str(data['urdf']),
                x=float(data.get('x', 0.0)),
                y=float(data.get('y', 0.0)),
                yaw=float(data.get('yaw', 0.0)),
                namespace=str(data.get('namespace', '')),
                id=str(data.get('id', '')),
            )
        except (ValueError, KeyError, TypeError, AttributeError) as e:
            raise SimError(f'not a spawn request: {e}') from None
        if not request.name:
            raise SimError('a spawn request needs an entity name')
        return request

    def validate(self) -> None:
        """A SimError unless the pose is finite and the namespace a ROS namespace: a request
        arrives from any peer, and a nan pose would stop the physics of every robot. Apart
        from `from_json` so that the refusal can still answer the request's id."""
        for axis in ('x', 'y', 'yaw'):
            value = getattr(self, axis)
            if not math.isfinite(value):
                raise SimError(f'{axis} must be a finite number, not {value}')
        if self.namespace.strip('/'):
            try:
                validate_namespace('/' + self.namespace.strip('/'))
            except NameValidationException as e:
                raise SimError(str(e)) from None


_DIFF_DRIVE = ('diff_drive', 'DiffDrive')
_RAYS = ('ray', 'gpu_ray', 'lidar', 'gpu_lidar')


def _number(element: ET.Element, path: str, default: float) -> float:
    text = element.findtext(path)
    try:
        return float(text) if text is not None and text.strip() else default
    except ValueError:
        raise SimError(f'<{path}> is not a number: {text!r}') from None


def _remapped(plugin: ET.Element, default: str, *names: str) -> str:
    """The topic a gazebo_ros plugin's `<remapping>name:=topic</remapping>` gives one of
    `names` (as `~/out`, `cmd_vel`, `odom`), else `default`."""
    for remap in plugin.iter('remapping'):
        key, sep, topic = (remap.text or '').strip().partition(':=')
        if sep and key.strip() in names:
            return topic.strip()
    return default


def _planar_offset(robot: Robot, base: str, link: str) -> tuple[float, float, float]:
    """(x, y, yaw) of `link` in `base`, from the fixed joints between them."""
    parent_joint = {j.child: j for j in robot.joints.values()}
    chain = []
    frame = link
    while frame != base and frame in parent_joint:
        chain.append(parent_joint[frame])
        frame = parent_joint[frame].parent
    x = y = yaw = 0.0
    for joint in reversed(chain):
        c, s = math.cos(yaw), math.sin(yaw)
        x, y = x + c * joint.xyz[0] - s * joint.xyz[1], y + s * joint.xyz[0] + c * joint.xyz[1]
        yaw += joint.rpy[2]
    return x, y, yaw


def _footprint(robot: Robot, base: str) -> float:
    for name in (base, 'base_link', 'chassis_link'):
        link = robot.links.get(name)
        for shape in link.collisions if link else ():
            g = shape.geometry
            if g.kind == 'box' and g.size:
                return math.hypot(g.size[0], g.size[1]) / 2
            if g.kind in ('cylinder', 'sphere') and g.radius:
                return g.radius
    return 0.2


def spec_from_urdf(text: str, name: str = '') -> RobotSpec:
    """The 2D robot a URDF (after xacro) with Gazebo diff-drive and ray-sensor tags makes."""
    try:
        robot = parse_urdf(text)
    except UrdfError as e:
        raise SimError(str(e)) from None
    drive: ET.Element | None = None
    laser: LaserSpec | None = None
    for gazebo in robot.gazebo:
        for plugin in gazebo.iter('plugin'):
            label = f'{plugin.get("filename", "")} {plugin.get("name", "")}'
            if drive is None and any(key in label for key in _DIFF_DRIVE):
                drive = plugin
    if drive is None:
        raise SimError(f'robot {robot.name!r}: no diff-drive plugin in its <gazebo> tags')
    base = (
        drive.findtext('robot_base_frame') or drive.findtext('child_frame_id') or robot.root
    ).strip()
    for gazebo in robot.gazebo:
        found = next((s for s in gazebo.iter('sensor') if s.get('type') in _RAYS), None)
        if found is None or laser is not None:
            continue
        sensor = found
        link = gazebo.get('reference', base)
        ray_plugin = sensor.find('plugin')
        topic = sensor.findtext('topic') or (
            _remapped(ray_plugin, 'scan', '~/out', 'out') if ray_plugin is not None else 'scan'
        )
        frame = (
            sensor.findtext('gz_frame_id')
            or (ray_plugin.findtext('frame_name') if ray_plugin is not None else None)
            or link
        )
        x, y, yaw = _planar_offset(robot, base, link)
        horizontal = './/scan/horizontal'
        laser = LaserSpec(
            topic=topic.strip(),
            frame_id=frame.strip(),
            samples=int(_number(sensor, f'{horizontal}/samples', 360)),
            angle_min=_number(sensor, f'{horizontal}/min_angle', -math.pi),
            angle_max=_number(sensor, f'{horizontal}/max_angle', math.pi),
            range_min=_number(sensor, './/range/min', 0.1),
            range_max=_number(sensor, './/range/max', 10.0),
            rate=_number(sensor, 'update_rate', 10.0),
            noise=_number(sensor, './/noise/stddev', 0.0),
            x=x,
            y=y,
            yaw=yaw,
        )
    if laser is None:
        raise SimError(f'robot {robot.name!r}: no ray sensor in its <gazebo> tags')
    separation = _number(drive, 'wheel_separation', 0.0)
    radius = _number(drive, 'wheel_radius', _number(drive, 'wheel_diameter', 0.0) / 2)
    if separation <= 0 or radius <= 0:
        raise SimError(
            f'robot {robot.name!r}: the diff-drive plugin needs wheel separation and size'
        )
    joints = tuple(
        Joint(
            j.name, j.parent, j.child, j.xyz, j.rpy, 'fixed' if j.type == 'fixed' else 'continuous'
        )
        for j in robot.joints.values()
    )
    wheels = tuple(
        (drive.findtext(tag) or '').strip()
        for tag in ('left_joint', 'right_joint')
        if drive.findtext(tag)
    )
    return RobotSpec(
        name=name or robot.name,
        banner=(
            f"ros2lite's 2D stand-in for the Gazebo simulation of {name or robot.name} "
            '(a flat world: no physics engine, the plugins\' topics, frames and rates)'
        ),
        limits=DriveLimits(
            separation,
            radius,
            footprint_radius=_footprint(robot, base),
            wheel_accel=_number(drive, 'max_wheel_acceleration', 0.0),
        ),
        start=Pose2D(),
        joints=joints,
        laser=laser,
        cmd_vel=(
            drive.findtext('command_topic')
            or drive.findtext('topic')
            or _remapped(drive, 'cmd_vel', 'cmd_vel', '~/cmd_vel')
        ).strip(),
        odom_topic=(
            drive.findtext('odometry_topic')
            or drive.findtext('odom_topic')
            or _remapped(drive, 'odom', 'odom', '~/odom')
        ).strip(),
        odom_frame=(
            drive.findtext('odometry_frame') or drive.findtext('frame_id') or 'odom'
        ).strip(),
        base_frame=base,
        odom_rate=_number(drive, 'update_rate', _number(drive, 'odom_publisher_frequency', 50.0)),
        publish_odom_tf=(drive.findtext('publish_odom_tf') or 'true').strip().lower() != 'false',
        wheel_joints=wheels or ('wheel_left_joint', 'wheel_right_joint'),
    )
