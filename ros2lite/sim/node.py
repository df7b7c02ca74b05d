"""The simulator's ROS node (`/gazebo`, as Gazebo's): robots in one world, their topics as
the robots' Gazebo plugins publish them, `/clock`, and Gazebo's reset and pause services.
The launch line's robot is there from the start; more join through the spawn topic
(`ros2lite.sim.spawn`: what `spawn_entity.py` and `ros_gz_sim create` send).

Physics runs on its own thread in fixed 10 ms steps of sim time, paced against the wall clock
by the real-time factor (0: as fast as it goes), and publishes from there: `/clock` every step,
each sensor when its sim-time period is due, so rates hold in sim time at any factor. Commands
and service calls arrive on the executor's thread and reach the physics thread under a lock.
A sensor with no subscriber is not drawn (the camera costs most), as Gazebo's sensors idle.
"""

from __future__ import annotations

import json
import math
import random
import threading
import time
from dataclasses import asdict, dataclass, replace
from typing import TYPE_CHECKING, Protocol

from ros2lite.msgs.builtin_interfaces.msg import Time
from ros2lite.msgs.geometry_msgs.msg import TransformStamped, Twist, TwistStamped
from ros2lite.msgs.nav_msgs.msg import Odometry
from ros2lite.msgs.rosgraph_msgs.msg import Clock
from ros2lite.msgs.sensor_msgs.msg import CameraInfo, Image, Imu, JointState, LaserScan
from ros2lite.msgs.std_msgs.msg import String
from ros2lite.msgs.std_srvs.srv import Empty
from ros2lite.msgs.tf2_msgs.msg import TFMessage
from ros2lite.node import Node
from ros2lite.qos import DurabilityPolicy, QoSProfile, qos_profile_sensor_data
from ros2lite.sim.drive import Base, Pose2D
from ros2lite.sim.errors import SimError
from ros2lite.sim.robots import RobotSpec, robot, urdf
from ros2lite.sim.sensors import LaserTables, render_camera, scan
from ros2lite.sim.spawn import SPAWN_TOPIC, SPAWNED_TOPIC, SpawnRequest, spec_from_urdf
from ros2lite.sim.worlds import open_world
from ros2lite.tf2.math import qmul, quaternion_from_rpy

if TYPE_CHECKING:
    from ros2lite.publisher import Publisher
    from ros2lite.sim.world import Grid

__all__ = ['STEP', 'Settings', 'SimNode']

STEP = 0.01  # s of sim time per physics step
_LATCHED = QoSProfile(depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL)
# the spawn answers stay for a spawner whose subscription matches after the answer went out
_SPAWNED_QOS = QoSProfile(depth=10, durability=DurabilityPolicy.TRANSIENT_LOCAL)


def _stamp(t: float) -> Time:
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


@dataclass(frozen=True)
class Settings:
    """What a launch line chooses; each is also a ROS parameter of the node (same name)."""

    robot_model: str = 'burger'
    world: str = 'turtlebot3_world'
    x_pose: float = math.nan  # nan: the robot's usual spawn point
    y_pose: float = math.nan
    yaw: float = 0.0
    real_time_factor: float = 1.0
    odom_noise: float = -1.0  # < 0: the robot's own
    publish_robot_state: bool = False
    seed: int = -1  # < 0: a new random seed each run
    scan_rate: float = 0.0  # Hz; <= 0: the robot's laser's own


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
        self._make_interfaces()

    def topic(self, name: str) -> str:
        """`name` under the robot's namespace (a spawned robot's `-robot_namespace`)."""
        if not self.namespace or name.startswith('/'):
            return name
        return f'/{self.namespace}/{name}'

    # -- set-up ------------------------------------------------------------------------------
    def _make_interfaces(self) -> None:
        spec, node, stage, topic = self.spec, self.node, self.stage, self.topic
        self.scan_pub = node.create_publisher(
            LaserScan, topic(spec.laser.topic), qos_profile_sensor_data
        )
        self.odom_pubs = [
            node.create_publisher(Odometry, topic(name), 10)
            for name in (spec.odom_topic, *spec.odom_copies)
        ]
        self.tf_pub = stage.tf_pub
        self.joints_pub = node.create_publisher(JointState, topic('joint_states'), 10)
        self.imu_pubs: list[Publisher[Imu]] = []
        if spec.imu is not None:
            self.imu_pubs = [
                node.create_publisher(Imu, topic(name), qos_profile_sensor_data)
                for name in (spec.imu.topic, *spec.imu_copies)
            ]
        self.image_pub: Publisher[Image] | None = None
        self.info_pub: Publisher[CameraInfo] | None = None
        if spec.camera is not None:
            self.image_pub = node.create_publisher(
                Image, topic(spec.camera.image_topic), qos_profile_sensor_data
            )
            self.info_pub = node.create_publisher(
                CameraInfo, topic(spec.camera.info_topic), qos_profile_sensor_data
            )
        inputs = spec.twist_mux or ((spec.cmd_vel, 0, 0.0),)
        self._mux: dict[str, tuple[int, float, float, float, float]] = {}
        for name, priority, timeout in inputs:
            self._mux[name] = (priority, timeout, -math.inf, 0.0, 0.0)
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
        spec, node = self.spec, self.node
        self.description_pub = node.create_publisher(
            String, self.topic('robot_description'), _LATCHED
        )
        self.description_pub.publish(String(data=urdf(spec)))
        static = node.create_publisher(TFMessage, '/tf_static', _LATCHED)
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

        self.node.create_subscription(Twist, self.topic(name), on_twist, 10)
        self.node.create_subscription(TwistStamped, self.topic(name), on_stamped, 10)

    def _command(self, name: str, linear: float, angular: float) -> None:
        """A twist on input `name`: it drives unless a higher-priority input is live."""
        if not (math.isfinite(linear) and math.isfinite(angular)):
            self.node.get_logger().warn('ignoring a velocity command that is not finite')
            return
        with self.stage.lock:
            now = self.stage.sim_time
            priority, timeout, _, _, _ = self._mux[name]
            self._mux[name] = (priority, timeout, now, linear, angular)
            for other, (p, t, heard, _, _) in self._mux.items():
                live = t <= 0 or now - heard <= t
                if other != name and p > priority and live and heard > -math.inf:
                    return
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


class SimNode(Node):
    """Robots in one world, simulated and published; `settings` are the parameters' defaults
    (a launch file's `parameters=` or `-p` override them). `robot_model:=none` starts an empty
    world, as Gazebo's server alone; robots join it through `SPAWN_TOPIC`."""

    def __init__(self, settings: Settings | None = None, *, node_name: str = 'gazebo') -> None:
        super().__init__(node_name)
        chosen = self._read_parameters(settings or Settings())
        self.world = open_world(chosen.world)
        self.real_time_factor = chosen.real_time_factor
        self.sim_time = 0.0
        self.paused = False
        self.lock = threading.Lock()
        self._reset_request: str | None = None
        self._stop = threading.Event()
        self._seed = None if chosen.seed < 0 else chosen.seed
        self.bodies: list[Body] = []
        self.clock_pub = self.create_publisher(Clock, '/clock', 10)
        self.tf_pub = self.create_publisher(TFMessage, '/tf', 100)
        self.create_service(Empty, '/reset_simulation', self._on_reset_simulation)
        self.create_service(Empty, '/reset_world', self._on_reset_world)
        self.create_service(Empty, '/pause_physics', self._on_pause)
        self.create_service(Empty, '/unpause_physics', self._on_unpause)
        self._spawned = self.create_publisher(String, SPAWNED_TOPIC, _SPAWNED_QOS)
        self.create_subscription(String, SPAWN_TOPIC, self._on_spawn, 10)
        if chosen.robot_model != 'none':
            self._add_first(chosen)
        else:
            self.get_logger().info(
                "ros2lite's 2D stand-in for the Gazebo simulation: an empty world, robots join "
                f'it through {SPAWN_TOPIC}'
            )
        self.get_logger().info(
            f'world {self.world.name!r}, real-time factor {self.real_time_factor:g}'
        )
        self._thread = threading.Thread(target=self._run, name='sim-physics', daemon=True)
        self._thread.start()

    def _add_first(self, chosen: Settings) -> None:
        spec = robot(chosen.robot_model)
        if chosen.scan_rate > 0:
            spec = replace(spec, laser=replace(spec.laser, rate=chosen.scan_rate))
        if chosen.odom_noise >= 0:
            spec = replace(spec, limits=replace(spec.limits, odom_noise=chosen.odom_noise))
        start = Pose2D(
            spec.start.x if math.isnan(chosen.x_pose) else chosen.x_pose,
            spec.start.y if math.isnan(chosen.y_pose) else chosen.y_pose,
            chosen.yaw,
        )
        body = Body(
            self, self, spec, start, self._seed, publish_robot_state=chosen.publish_robot_state
        )
        self.bodies.append(body)
        self.get_logger().info(spec.banner)
        self.get_logger().info(f'{spec.name} at ({start.x:.2f}, {start.y:.2f})')

    @property
    def spec(self) -> RobotSpec:
        """The first robot's spec (the one the launch line named)."""
        return self.bodies[0].spec

    @property
    def base(self) -> Base:
        """The first robot's drive."""
        return self.bodies[0].base

    def _read_parameters(self, defaults: Settings) -> Settings:
        values: dict[str, object] = {}
        for name, default in asdict(defaults).items():
            value = self.declare_parameter(name, default).value
            if isinstance(default, float) and isinstance(value, int):
                value = float(value)
            if type(value) is not type(default):
                raise SimError(
                    f'parameter {name!r} must be a {type(default).__name__}, not {value!r}'
                )
            values[name] = value
        return Settings(**values)  # type: ignore[arg-type]

    # -- spawning (executor thread) ----------------------------------------------------------
    def _on_spawn(self, msg: String) -> None:
        """A spawner's request (see `SpawnRequest`): the robot joins, or one line says why not."""
        request: SpawnRequest | None = None
        try:
            request = SpawnRequest.from_json(msg.data)
            self.spawn(request)
        except SimError as e:
            name = request.name if request is not None else '?'
            self.get_logger().error(f'cannot spawn {name!r}: {e}')
            self._answer(request, str(e))
            return
        self._answer(request, '')

    def _answer(self, request: SpawnRequest | None, error: str) -> None:
        if request is None:
            return
        answer = {'id': request.id, 'name': request.name, 'ok': not error, 'message': error}
        self._spawned.publish(String(data=json.dumps(answer)))

    def spawn(self, request: SpawnRequest) -> None:
        """Add the robot `request` describes to the running world."""
        if any(b.spec.name == request.name for b in self.bodies):
            raise SimError(f'an entity named {request.name!r} is already in the world')
        spec = replace(spec_from_urdf(request.urdf, request.name), start=Pose2D())
        start = Pose2D(request.x, request.y, request.yaw)
        body = Body(self, self, spec, start, self._seed, namespace=request.namespace)
        with self.lock:
            self.bodies.append(body)
        self.get_logger().info(
            f'spawned {spec.name!r} at ({start.x:.2f}, {start.y:.2f}): '
            f'{body.topic(spec.cmd_vel)} drives it, {body.topic(spec.laser.topic)} at '
            f'{spec.laser.rate:g} Hz'
        )

    # -- services (executor thread) ----------------------------------------------------------
    def _on_reset_simulation(
        self, request: Empty.Request, response: Empty.Response
    ) -> Empty.Response:
        with self.lock:
            self._reset_request = 'simulation'
        return response

    def _on_reset_world(self, request: Empty.Request, response: Empty.Response) -> Empty.Response:
        with self.lock:
            self._reset_request = 'world'
        return response

    def _on_pause(self, request: Empty.Request, response: Empty.Response) -> Empty.Response:
        with self.lock:
            self.paused = True
        return response

    def _on_unpause(self, request: Empty.Request, response: Empty.Response) -> Empty.Response:
        with self.lock:
            self.paused = False
        return response

    # -- the physics thread ------------------------------------------------------------------
    def _run(self) -> None:
        anchor_wall = time.monotonic()
        anchor_sim = 0.0
        try:
            while not self._stop.is_set() and self.context.ok():
                with self.lock:
                    paused = self.paused
                    reset = self._reset_request
                    self._reset_request = None
                    if reset is not None:
                        self._reset(reset)
                        anchor_wall, anchor_sim = time.monotonic(), self.sim_time
                    if not paused:
                        self.sim_time = round(self.sim_time + STEP, 9)
                        for body in self.bodies:
                            body.step(self.sim_time)
                    bodies = list(self.bodies)
                if paused:
                    anchor_wall, anchor_sim = time.monotonic(), self.sim_time
                    self._stop.wait(0.02)
                    continue
                stamp = _stamp(self.sim_time)
                self.clock_pub.publish(Clock(clock=stamp))
                for body in bodies:
                    body.publish(self.sim_time, stamp)
                rtf = self.real_time_factor
                if rtf > 0:
                    delay = anchor_wall + (self.sim_time - anchor_sim) / rtf - time.monotonic()
                    if delay > 0:
                        self._stop.wait(delay)
                    elif delay < -0.5:  # fell behind: do not race to catch up
                        anchor_wall, anchor_sim = time.monotonic(), self.sim_time
        except Exception as e:  # the context went away under a publish at shutdown
            if self.context.ok():
                self.get_logger().error(f'simulation stopped: {e}')

    def _reset(self, kind: str) -> None:
        if kind == 'simulation':
            self.sim_time = 0.0
        for body in self.bodies:
            body.reset(kind)

    # -- the end -----------------------------------------------------------------------------
    def destroy_node(self) -> None:
        self._stop.set()
        if self._thread.is_alive() and self._thread is not threading.current_thread():
            self._thread.join(2.0)
        super().destroy_node()


def _transform(
    parent: str,
    child: str,
    xyz: tuple[float, float, float],
    rpy: tuple[float, float, float],
    t: float,
) -> TransformStamped:
    msg = TransformStamped()
    msg.header.stamp = _stamp(t)
    msg.header.frame_id = parent
    msg.child_frame_id = child
    msg.transform.translation.x, msg.transform.translation.y, msg.transform.translation.z = xyz
    q = quaternion_from_rpy(*rpy)
    rot = msg.transform.rotation
    rot.x, rot.y, rot.z, rot.w = q
    return msg


def _wrap(angle: float) -> float:
    return math.atan2(math.sin(angle), math.cos(angle))
