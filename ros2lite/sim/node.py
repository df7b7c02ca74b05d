"""The simulator's ROS node (`/gazebo`, as Gazebo's): robots in one world, their topics as
the robots' Gazebo plugins publish them, `/clock`, and Gazebo's reset and pause services.
The launch line's robot is there from the start; more join through the spawn topic
(`ros2lite.sim.spawn`: what `spawn_entity.py` and `ros_gz_sim create` send). Each robot is a
`ros2lite.sim.body.Body`: its inputs, outputs and their rates live there.

Physics runs on its own thread in fixed 10 ms steps of sim time, paced against the wall clock
by the real-time factor (0: as fast as it goes), and publishes from there: `/clock` every step,
each sensor when its sim-time period is due, so rates hold in sim time at any factor. Commands
and service calls arrive on the executor's thread and reach the physics thread under a lock.
A sensor with no subscriber is not drawn (the camera costs most), as Gazebo's sensors idle.
"""

from __future__ import annotations

import json
import math
import threading
import time
from dataclasses import asdict, dataclass, replace

from ros2lite.exceptions import Ros2liteError
from ros2lite.msgs.rcl_interfaces.msg import ParameterDescriptor
from ros2lite.msgs.rosgraph_msgs.msg import Clock
from ros2lite.msgs.std_msgs.msg import String
from ros2lite.msgs.std_srvs.srv import Empty
from ros2lite.msgs.tf2_msgs.msg import TFMessage
from ros2lite.node import Node
from ros2lite.qos import DurabilityPolicy, QoSProfile
from ros2lite.sim.body import STEP, Body, stamp_of
from ros2lite.sim.drive import Base, Pose2D
from ros2lite.sim.errors import SimError
from ros2lite.sim.robots import RobotSpec, robot
from ros2lite.sim.spawn import SPAWN_TOPIC, SPAWNED_TOPIC, SpawnRequest, spec_from_urdf
from ros2lite.sim.worlds import open_world

__all__ = ['STEP', 'Settings', 'SimNode']

# the spawn answers stay for a spawner whose subscription matches after the answer went out
_SPAWNED_QOS = QoSProfile(depth=10, durability=DurabilityPolicy.TRANSIENT_LOCAL)


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


class SimNode(Node):
    """Robots in one world, simulated and published; `settings` are the parameters' defaults
    (a launch file's `parameters=` or `-p` override them). `robot_model:=none` starts an empty
    world, as Gazebo's server alone; robots join it through `SPAWN_TOPIC`."""

    def __init__(self, settings: Settings | None = None, *, node_name: str = 'gazebo') -> None:
        super().__init__(node_name)
        self._stop = threading.Event()
        self._thread: threading.Thread | None = None  # until the world is made
        chosen = self._read_parameters(settings or Settings())
        self.world = open_world(chosen.world)
        self.real_time_factor = chosen.real_time_factor
        self.sim_time = 0.0
        self.paused = False
        self.lock = threading.Lock()
        self._reset_request: str | None = None
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
        self._thread = thread = threading.Thread(target=self._run, name='sim-physics', daemon=True)
        thread.start()

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
            # a decimal setting takes a whole number too (`real_time_factor:=10`), as the
            # conversion below makes it a float: rclpy's typing would refuse it
            descriptor = ParameterDescriptor(dynamic_typing=isinstance(default, float))
            value = self.declare_parameter(name, default, descriptor).value
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
        except (Ros2liteError, ValueError) as e:  # a peer's bad request: one line, dropped
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
        """Add the robot `request` describes to the running world; a SimError (or a name
        error, for a URDF's topic) says why not, and leaves nothing of the robot behind."""
        request.validate()
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
                stamp = stamp_of(self.sim_time)
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
        thread = self._thread
        if thread is not None and thread.is_alive() and thread is not threading.current_thread():
            thread.join(2.0)
        super().destroy_node()
