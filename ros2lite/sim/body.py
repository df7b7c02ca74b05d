"""One robot in the simulated world: its drive, the velocity inputs it listens to (a twist
multiplexer's, when the robot has one), and its outputs as the robot's Gazebo plugins publish
them: odometry and its TF, joint states, laser, IMU, camera, and when each is due in sim time.

Apart from `node` (the world's node, its services, spawning and physics thread) because a
body is the part that grows with every robot and sensor; it reaches the node's shared state
through `Stage`, so it does not name the node's class.
"""

from __future__ import annotations

import math
import random
import threading
from collections.abc import Callable
from typing import TYPE_CHECKING, Any, Protocol

from ros2lite.msgs.builtin_interfaces.msg import Time
from ros2lite.msgs.geometry_msgs.msg import TransformStamped, Twist, TwistStamped
from ros2lite.msgs.nav_msgs.msg import Odometry
from ros2lite.msgs.sensor_msgs.msg import CameraInfo, Image, Imu, JointState, LaserScan
from ros2lite.msgs.std_msgs.msg import String
from ros2lite.msgs.tf2_msgs.msg import TFMessage
from ros2lite.qos import DurabilityPolicy, QoSProfile, qos_profile_sensor_data
from ros2lite.sim.drive import Base, Pose2D
from ros2lite.sim.mux import TwistMux
from ros2lite.sim.robots import RobotSpec, urdf
from ros2lite.sim.sensors import LaserTables, render_camera, scan
from ros2lite.tf2.math import qmul, quaternion_from_rpy

if TYPE_CHECKING:
    from ros2lite.node import Node
    from ros2lite.publisher import Publisher
    from ros2lite.sim.world import Grid
    from ros2lite.subscription import Subscription
    from ros2lite.type_support import MsgT

__all__ = ['STEP', 'Body', 'Stage', 'stamp_of']

STEP = 0.01  # s of sim time per physics step
_LATCHED = QoSProfile(depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL)


def stamp_of(t: float) -> Time:
    """Sim time `t` (seconds) as a message's stamp."""
    sec = math.floor(t)
    return Time(sec=int(sec), nanosec=min(999_999_999, round((t - sec) * 1e9)))


class _Due:
    """When a periodic output is next due, in sim time."""

    def __init__(self, rate: float) -> None:
        self.period = 1.0 / rate if rate > 0 else math.inf
        self.next = 0.0

    def check(self, now: float) -> bool:
        if now + 1e-9 < self.next:
            return False
        self.next += self.period
        if self.next <= now:  # after a pause or a reset: no burst
            self.next = now + self.period
        return True


class Stage(Protocol):
    """What a body reads of the world it is in (the simulator node is one): the lock the
    physics thread steps under, the grid, sim time, and the `/tf` publisher bodies share."""

    lock: threading.Lock
    world: Grid
    sim_time: float
    tf_pub: Publisher[TFMessage]


class Body:
    """One robot in the world: its drive, its inputs and outputs, and when each is due."""

    def __init__(
        self,
        node: Node,
        stage: Stage,
        spec: RobotSpec,
        start: Pose2D,
        seed: int | None,
        *,
        namespace: str = '',
        publish_robot_state: bool = False,
    ) -> None:
        self.node = node
        self.stage = stage
        self.spec = spec
        self.namespace = namespace.strip('/')
        self.base = Base(spec.limits, start, seed)
        self.rng = random.Random(seed)
        self._tables = LaserTables(spec.laser)
        self._last_linear = 0.0
        self._publish_robot_state = publish_robot_state
        self._pubs: list[Publisher[Any]] = []
        self._subs: list[Subscription[Any]] = []
        try:
            self._make_interfaces()
        except BaseException:  # a name the node refuses: no half-built robot stays behind
            self.destroy()
            raise

    def destroy(self) -> None:
        """Remove the robot's publishers and subscriptions from the node."""
        for sub in self._subs:
            self.node.destroy_subscription(sub)
        for pub in self._pubs:
            self.node.destroy_publisher(pub)
        self._subs.clear()
        self._pubs.clear()

    def topic(self, name: str) -> str:
        """`name` under the robot's namespace (a spawned robot's `-robot_namespace`)."""
        if not self.namespace or name.startswith('/'):
            return name
        return f'/{self.namespace}/{name}'

    # -- set-up ------------------------------------------------------------------------------
    def _publisher(self, msg_type: type[MsgT], name: str, qos: QoSProfile | int) -> Publisher[MsgT]:
        pub = self.node.create_publisher(msg_type, name, qos)
        self._pubs.append(pub)
        return pub

    def _subscription(
        self, msg_type: type[MsgT], name: str, callback: Callable[[MsgT], None], qos: int
    ) -> None:
        self._subs.append(self.node.create_subscription(msg_type, name, callback, qos))

    def _make_interfaces(self) -> None:
        spec, stage, topic = self.spec, self.stage, self.topic
        self.scan_pub = self._publisher(LaserScan, topic(spec.laser.topic), qos_profile_sensor_data)
        self.odom_pubs = [
            self._publisher(Odometry, topic(name), 10)
            for name in (spec.odom_topic, *spec.odom_copies)
        ]
        self.tf_pub = stage.tf_pub
        self.joints_pub = self._publisher(JointState, topic('joint_states'), 10)
        self.imu_pubs: list[Publisher[Imu]] = []
        if spec.imu is not None:
            self.imu_pubs = [
                self._publisher(Imu, topic(name), qos_profile_sensor_data)
                for name in (spec.imu.topic, *spec.imu_copies)
            ]
        self.image_pub: Publisher[Image] | None = None
        self.info_pub: Publisher[CameraInfo] | None = None
        if spec.camera is not None:
            self.image_pub = self._publisher(
                Image, topic(spec.camera.image_topic), qos_profile_sensor_data
            )
            self.info_pub = self._publisher(
                CameraInfo, topic(spec.camera.info_topic), qos_profile_sensor_data
            )
        self._mux = TwistMux(spec.twist_mux or ((spec.cmd_vel, 0, 0.0),))
        for name in self._mux.names:
            self._listen(name)
        self._due = {
            'scan': _Due(spec.laser.rate),
            'odom': _Due(spec.odom_rate),
            'joints': _Due(spec.joint_states_rate),
            'imu': _Due(spec.imu.rate if spec.imu else 0.0),
            'camera': _Due(spec.camera.rate if spec.camera else 0.0),
        }
        if self._publish_robot_state:
            self._publish_description()

    def _publish_description(self) -> None:
        """The robot's description and fixed frames, for when no robot_state_publisher runs."""
        spec = self.spec
        self.description_pub = self._publisher(String, self.topic('robot_description'), _LATCHED)
        self.description_pub.publish(String(data=urdf(spec)))
        static = self._publisher(TFMessage, '/tf_static', _LATCHED)
        transforms = [
            _transform(j.parent, j.child, j.xyz, j.rpy, 0.0)
            for j in spec.joints
            if j.kind == 'fixed'
        ]
        static.publish(TFMessage(transforms=transforms))
        self.static_pub = static

    # -- inputs (executor thread) ------------------------------------------------------------
    def _listen(self, name: str) -> None:
        """Subscribe to a velocity input as Twist and as TwistStamped."""

        def on_twist(msg: Twist) -> None:
            self._command(name, msg.linear.x, msg.angular.z)

        def on_stamped(msg: TwistStamped) -> None:
            self._command(name, msg.twist.linear.x, msg.twist.angular.z)

        self._subscription(Twist, self.topic(name), on_twist, 10)
        self._subscription(TwistStamped, self.topic(name), on_stamped, 10)

    def _command(self, name: str, linear: float, angular: float) -> None:
        """A twist on input `name`: it drives unless a higher-priority input is live."""
        if not (math.isfinite(linear) and math.isfinite(angular)):
            self.node.get_logger().warn('ignoring a velocity command that is not finite')
            return
        with self.stage.lock:
            now = self.stage.sim_time
            if self._mux.admits(name, now):
                self.base.set_command(linear, angular, now)

    # -- the physics thread ------------------------------------------------------------------
    def step(self, now: float) -> None:
        """One physics step (under the stage's lock); a collision is said once."""
        if self.base.step(STEP, now, self.stage.world):
            p = self.base.pose
            self.node.get_logger().warn(
                f'{self.spec.name} hit an obstacle at ({p.x:.2f}, {p.y:.2f}): stopped'
            )

    def reset(self, kind: str) -> None:
        self.base.reset()
        if kind == 'simulation':
            for due in self._due.values():
                due.next = 0.0

    def publish(self, now: float, stamp: Time) -> None:
        due = self._due
        if due['odom'].check(now):
            self._publish_odom(stamp)
        if due['joints'].check(now):
            self._publish_joints(stamp)
        if due['scan'].check(now) and self.scan_pub.get_subscription_count() > 0:
            self._publish_scan(stamp)
        imu = self.imu_pubs
        if imu and due['imu'].check(now) and any(p.get_subscription_count() for p in imu):
            self._publish_imu(stamp)
        if self.image_pub is not None and due['camera'].check(now):
            self._publish_camera(stamp)

    # -- outputs -----------------------------------------------------------------------------
    def _publish_odom(self, stamp: Time) -> None:
        spec, base = self.spec, self.base
        odom = base.odom
        msg = Odometry()
        msg.header.stamp = stamp
        msg.header.frame_id = spec.odom_frame
        msg.child_frame_id = spec.base_frame
        msg.pose.pose.position.x = odom.x
        msg.pose.pose.position.y = odom.y
        q = quaternion_from_rpy(0.0, 0.0, odom.yaw)
        o = msg.pose.pose.orientation
        o.x, o.y, o.z, o.w = q
        msg.twist.twist.linear.x = base.odom_linear
        msg.twist.twist.angular.z = base.odom_angular
        cov = [0.0] * 36
        cov[0] = cov[7] = cov[14] = cov[21] = cov[28] = cov[35] = 1e-5
        msg.pose.covariance = cov
        msg.twist.covariance = cov
        for pub in self.odom_pubs:
            pub.publish(msg)
        if spec.publish_odom_tf:
            t = _transform(
                spec.odom_frame, spec.base_frame, (odom.x, odom.y, 0.0), (0.0, 0.0, odom.yaw), 0.0
            )
            t.header.stamp = stamp
            self.tf_pub.publish(TFMessage(transforms=[t]))

    def _publish_joints(self, stamp: Time) -> None:
        msg = JointState()
        msg.header.stamp = stamp
        names = self.spec.wheel_joints
        sides = [0 if 'left' in name else 1 for name in names]
        angles = [self.base.wheel_angle[side] for side in sides]
        msg.name = list(names)
        msg.position = [_wrap(a) for a in angles]
        r = self.spec.limits.wheel_radius
        msg.velocity = [self.base.wheel_speed[side] / r for side in sides]
        msg.effort = [0.0] * len(names)
        self.joints_pub.publish(msg)
        if self._publish_robot_state:
            transforms = []
            by_name = {j.name: j for j in self.spec.joints}
            for name, angle in zip(names, angles, strict=True):
                joint = by_name.get(name)
                if joint is None:
                    continue
                # the wheel turns about its own z axis, after the joint's fixed rotation
                t = self._wheel_transform(joint.parent, joint.child, joint.xyz, joint.rpy, angle)
                t.header.stamp = stamp
                transforms.append(t)
            if transforms:
                self.tf_pub.publish(TFMessage(transforms=transforms))

    def _wheel_transform(
        self,
        parent: str,
        child: str,
        xyz: tuple[float, float, float],
        rpy: tuple[float, float, float],
        angle: float,
    ) -> TransformStamped:
        msg = _transform(parent, child, xyz, rpy, 0.0)
        fixed = quaternion_from_rpy(*rpy)
        turn = quaternion_from_rpy(0.0, 0.0, angle)
        rot = msg.transform.rotation
        rot.x, rot.y, rot.z, rot.w = qmul(fixed, turn)
        return msg

    def _publish_scan(self, stamp: Time) -> None:
        spec = self.spec.laser
        with self.stage.lock:
            pose = Pose2D(self.base.pose.x, self.base.pose.y, self.base.pose.yaw)
        msg = LaserScan()
        msg.header.stamp = stamp
        msg.header.frame_id = spec.frame_id
        msg.angle_min = spec.angle_min
        msg.angle_max = spec.angle_max
        msg.angle_increment = spec.increment
        msg.time_increment = 0.0
        msg.scan_time = 0.0
        msg.range_min = spec.range_min
        msg.range_max = spec.range_max
        msg.ranges = scan(self.stage.world, self._tables, pose.x, pose.y, pose.yaw, self.rng)
        msg.intensities = [0.0] * spec.samples
        self.scan_pub.publish(msg)

    def _publish_imu(self, stamp: Time) -> None:
        spec = self.spec.imu
        if spec is None:
            return
        base = self.base
        gauss = self.rng.gauss
        msg = Imu()
        msg.header.stamp = stamp
        msg.header.frame_id = spec.frame_id
        q = quaternion_from_rpy(0.0, 0.0, base.pose.yaw)
        o = msg.orientation
        o.x, o.y, o.z, o.w = q
        g, a = spec.gyro_noise, spec.accel_noise
        msg.angular_velocity.x = gauss(0.0, g) if g else 0.0
        msg.angular_velocity.y = gauss(0.0, g) if g else 0.0
        msg.angular_velocity.z = base.angular + (gauss(0.0, g) if g else 0.0)
        forward = (base.linear - self._last_linear) * spec.rate
        self._last_linear = base.linear
        msg.linear_acceleration.x = forward + (gauss(0.0, a) if a else 0.0)
        msg.linear_acceleration.y = base.linear * base.angular + (gauss(0.0, a) if a else 0.0)
        msg.linear_acceleration.z = 9.80665 + (gauss(0.0, a) if a else 0.0)
        msg.angular_velocity_covariance = [g * g, 0.0, 0.0, 0.0, g * g, 0.0, 0.0, 0.0, g * g]
        msg.linear_acceleration_covariance = [a * a, 0.0, 0.0, 0.0, a * a, 0.0, 0.0, 0.0, a * a]
        for pub in self.imu_pubs:
            pub.publish(msg)

    def _publish_camera(self, stamp: Time) -> None:
        spec = self.spec.camera
        if spec is None or self.image_pub is None or self.info_pub is None:
            return
        if self.info_pub.get_subscription_count() > 0:
            info = CameraInfo()
            info.header.stamp = stamp
            info.header.frame_id = spec.frame_id
            info.width, info.height = spec.width, spec.height
            info.distortion_model = 'plumb_bob'
            info.d = [0.0] * 5
            f, cx, cy = spec.focal, spec.width / 2, spec.height / 2
            info.k = [f, 0.0, cx, 0.0, f, cy, 0.0, 0.0, 1.0]
            info.r = [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0]
            info.p = [f, 0.0, cx, 0.0, 0.0, f, cy, 0.0, 0.0, 0.0, 1.0, 0.0]
            self.info_pub.publish(info)
        if self.image_pub.get_subscription_count() == 0:
            return
        pose = self.base.pose
        msg = Image()
        msg.header.stamp = stamp
        msg.header.frame_id = spec.frame_id
        msg.width, msg.height = spec.width, spec.height
        msg.encoding = 'rgb8'
        msg.step = spec.width * 3
        msg.data = render_camera(self.stage.world, spec, pose.x, pose.y, pose.yaw)
        self.image_pub.publish(msg)


def _transform(
    parent: str,
    child: str,
    xyz: tuple[float, float, float],
    rpy: tuple[float, float, float],
    t: float,
) -> TransformStamped:
    msg = TransformStamped()
    msg.header.stamp = stamp_of(t)
    msg.header.frame_id = parent
    msg.child_frame_id = child
    msg.transform.translation.x, msg.transform.translation.y, msg.transform.translation.z = xyz
    q = quaternion_from_rpy(*rpy)
    rot = msg.transform.rotation
    rot.x, rot.y, rot.z, rot.w = q
    return msg


def _wrap(angle: float) -> float:
    return math.atan2(math.sin(angle), math.cos(angle))
