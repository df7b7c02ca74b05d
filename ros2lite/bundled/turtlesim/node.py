"""The `/turtlesim` node: Jazzy turtlesim's ROS interface over the `sim.World` library.

Everything runs on the node's executor: a 16 ms timer steps the world and publishes each
turtle's pose and colour; services and the rotate_absolute action feed requests into the
world, which applies them at the next step as turtlesim does. Views (window, terminal) never
touch this thread: they read `frame` (replaced whole after every step) and drain the canvas
strokes, so drawing can never hold the simulation up.

Types are the `turtlesim` package's, as the Jazzy node advertises them, or with
``ROS_DISTRO=kilted`` (or rolling) `turtlesim_msgs`', where the interfaces moved after Jazzy
(:mod:`ros2lite.bundled.turtlesim.interfaces`).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, cast

from ros2lite.action import ActionServer, CancelResponse
from ros2lite.action.server import GoalResponse, ServerGoalHandle
from ros2lite.bundled.turtlesim import sim
from ros2lite.bundled.turtlesim.interfaces import (
    Color,
    Kill,
    Pose,
    RotateAbsolute,
    SetPen,
    Spawn,
    TeleportAbsolute,
    TeleportRelative,
)
from ros2lite.msgs.geometry_msgs.msg import Twist
from ros2lite.msgs.rcl_interfaces.msg import (
    IntegerRange,
    ParameterDescriptor,
    ParameterEvent,
)
from ros2lite.msgs.std_srvs.srv import Empty
from ros2lite.node import Node
from ros2lite.parameter import Parameter
from ros2lite.qos import QoSProfile, ReliabilityPolicy
from ros2lite.task import Future

# turtlesim's topic QoS (keep last 10, reliable), and its /parameter_events subscription's
TOPIC_QOS = 10
STATS_PERIOD = 5.0  # s between the debug lines with step and render rates
PARAMETER_EVENTS_QOS = QoSProfile(depth=100, reliability=ReliabilityPolicy.BEST_EFFORT)


# the largest value a float32 field (Pose.x, Pose.linear_velocity, …) holds
_FLOAT32_MAX = 3.4028234663852886e38


@dataclass(frozen=True)
class TurtleView:
    """What a view draws of one turtle."""

    name: str
    x: float
    y: float
    theta: float
    sprite: int


@dataclass(frozen=True)
class Frame:
    """The world as a view sees it after a step; replaced whole, never changed."""

    turtles: tuple[TurtleView, ...]
    background: tuple[int, int, int]
    steps: int


if TYPE_CHECKING:
    from typing_extensions import Unpack

    from ros2lite.node_options import NodeOptions
    from ros2lite.service import Service

    _RotateHandle = ServerGoalHandle[
        RotateAbsolute.Goal, RotateAbsolute.Result, RotateAbsolute.Feedback
    ]


class _TurtleInterface:
    """One turtle's topics, services and action on the node (created on spawn, gone on kill)."""

    def __init__(self, node: TurtlesimNode, turtle: sim.Turtle) -> None:
        self.node = node
        self.turtle = turtle
        name = turtle.name
        self.cmd_vel = node.create_subscription(Twist, f'{name}/cmd_vel', self._on_twist, TOPIC_QOS)
        self.pose = node.create_publisher(Pose, f'{name}/pose', TOPIC_QOS)
        self.color = node.create_publisher(Color, f'{name}/color_sensor', TOPIC_QOS)
        self.services: list[Service[Any, Any]] = [
            node.create_service(SetPen, f'{name}/set_pen', self._on_set_pen),
            node.create_service(
                TeleportRelative, f'{name}/teleport_relative', self._on_teleport_relative
            ),
            node.create_service(
                TeleportAbsolute, f'{name}/teleport_absolute', self._on_teleport_absolute
            ),
        ]
        self.rotate = ActionServer(
            node,
            RotateAbsolute,
            f'{name}/rotate_absolute',
            self._execute,
            goal_callback=self._on_goal,
            handle_accepted_callback=self._on_accepted,
            cancel_callback=self._on_cancel,
        )
        self._results: dict[_RotateHandle, Future[RotateAbsolute.Result]] = {}

    # -- inputs ----------------------------------------------------------------------------
    def _on_twist(self, msg: Twist) -> None:
        if not self.node.finite(
            'velocity command',
            linear_x=msg.linear.x,
            linear_y=msg.linear.y,
            angular_z=msg.angular.z,
        ):
            return
        world = self.node.world
        aborted = self.turtle.command(
            msg.linear.x, msg.linear.y, msg.angular.z, world.time, world.holonomic
        )
        if aborted is not None:
            self.node.get_logger().warn(
                'Velocity command received during rotation goal. Aborting goal'
            )
            self.finish(aborted.goal, 'aborted')

    def _on_set_pen(self, request: SetPen.Request, response: SetPen.Response) -> SetPen.Response:
        self.turtle.set_pen(request.r, request.g, request.b, request.width, bool(request.off))
        return response

    def _on_teleport_relative(
        self, request: TeleportRelative.Request, response: TeleportRelative.Response
    ) -> TeleportRelative.Response:
        if self.node.finite('teleport', linear=request.linear, angular=request.angular):
            self.turtle.teleport_relative(request.linear, request.angular)
        return response

    def _on_teleport_absolute(
        self, request: TeleportAbsolute.Request, response: TeleportAbsolute.Response
    ) -> TeleportAbsolute.Response:
        if self.node.finite('teleport', x=request.x, y=request.y, theta=request.theta):
            self.turtle.teleport_absolute(request.x, request.y, request.theta)
        return response

    # -- rotate_absolute: the world works the goal; the execute callback waits for its end ---
    def _on_goal(self, goal: RotateAbsolute.Goal) -> GoalResponse:
        if self.node.finite('rotation goal', theta=goal.theta):
            return GoalResponse.ACCEPT
        return GoalResponse.REJECT

    def _on_accepted(self, handle: _RotateHandle) -> None:
        result: Future[RotateAbsolute.Result] = Future()
        self._results[handle] = result
        previous = self.turtle.start_goal(sim.RotateGoal(handle.request.theta, token=handle))
        if previous is not None:
            self.node.get_logger().warn(
                'Rotation goal received before a previous goal finished. Aborting previous goal'
            )
            self.finish(previous.goal, 'aborted')
        handle.execute()

    async def _execute(self, handle: _RotateHandle) -> RotateAbsolute.Result:
        future = self._results.get(handle)
        if future is None:  # ended before it started executing
            return RotateAbsolute.Result()
        result = await future
        return result if result is not None else RotateAbsolute.Result()

    def _on_cancel(self, handle: _RotateHandle) -> CancelResponse:
        goal = self.turtle.goal
        if goal is not None and goal.token == handle:
            goal.cancel_requested = True
        return CancelResponse.ACCEPT

    def feedback(self, goal: sim.RotateGoal, remaining: float) -> None:
        handle = cast('_RotateHandle', goal.token)  # the token is the goal's handle
        handle.publish_feedback(RotateAbsolute.Feedback(remaining=remaining))

    def finish(self, goal: sim.RotateGoal, outcome: str) -> None:
        """End the goal's ROS side: its state, then its result (`delta`) to the waiting
        execute callback."""
        handle = cast('_RotateHandle', goal.token)
        transition = {
            'succeeded': handle.succeed,
            'canceled': handle.canceled,
            'aborted': handle.abort,
        }[outcome]
        try:
            transition()
        except RuntimeError:  # e.g. canceled but no cancel was accepted: end it anyway
            if handle.is_active:
                handle.abort()
        future = self._results.pop(handle, None)
        if future is not None and not future.done():
            future.set_result(RotateAbsolute.Result(delta=goal.delta))

    # -- outputs ---------------------------------------------------------------------------
    def publish(self, update: sim.TurtleUpdate) -> None:
        p = update.pose
        self.pose.publish(
            Pose(
                x=p.x,
                y=p.y,
                theta=p.theta,
                linear_velocity=p.linear_velocity,
                angular_velocity=p.angular_velocity,
            )
        )
        r, g, b = update.color
        self.color.publish(Color(r=r, g=g, b=b))

    def destroy(self) -> None:
        if self.turtle.goal is not None:
            goal, self.turtle.goal = self.turtle.goal, None
            self.finish(goal, 'aborted')
        node = self.node
        node.destroy_subscription(self.cmd_vel)
        node.destroy_publisher(self.pose)
        node.destroy_publisher(self.color)
        for service in self.services:
            node.destroy_service(service)
        self.rotate.destroy()


def _channel(description: str) -> ParameterDescriptor:
    return ParameterDescriptor(
        description=description,
        integer_range=[IntegerRange(from_value=0, to_value=255, step=1)],
    )


class TurtlesimNode(Node):
    """Jazzy's `/turtlesim`: parameters, the four world services, and one interface per
    turtle, stepped every 16 ms."""

    def __init__(self, *, world: sim.World | None = None, **kwargs: Unpack[NodeOptions]) -> None:
        super().__init__('turtlesim', **kwargs)
        self.world = world or sim.World()
        self.revision = 0  # bumped on every change a view could show
        r, g, b = sim.DEFAULT_BACKGROUND
        self.declare_parameter('background_r', r, _channel('Red channel of the background color'))
        self.declare_parameter('background_g', g, _channel('Green channel of the background color'))
        self.declare_parameter('background_b', b, _channel('Blue channel of the background color'))
        self.declare_parameter(
            'holonomic',
            False,
            ParameterDescriptor(description='If true, then turtles will be holonomic'),
        )
        self._apply_parameters(
            self.get_parameters(['background_r', 'background_g', 'background_b', 'holonomic'])
        )
        self.add_post_set_parameters_callback(self._apply_parameters)

        self.create_service(Empty, 'clear', self._on_clear)
        self.create_service(Empty, 'reset', self._on_reset)
        self.create_service(Spawn, 'spawn', self._on_spawn)
        self.create_service(Kill, 'kill', self._on_kill)
        self.create_subscription(
            ParameterEvent, '/parameter_events', self._on_parameter_event, PARAMETER_EVENTS_QOS
        )
        self.get_logger().info(
            f'Starting turtlesim with node name {self.get_fully_qualified_name()}'
        )
        self._interfaces: dict[str, _TurtleInterface] = {}
        self.frame = Frame((), self.world.background, 0)
        # step timing, for the measured real-time claim: (wall time, steps) at start
        self.step_seconds = 0.0
        self.render_frames = 0  # a view counts its redraws here
        self._started = (time.monotonic(), self.world.steps)
        self._last_stats = (time.monotonic(), self.world.steps, 0, 0.0)
        self._spawn('', sim.WIDTH / 2.0, sim.HEIGHT / 2.0, 0.0)
        self._update_frame()
        self.step_timer = self.create_timer(sim.DT, self.step)
        self.stats_timer = self.create_timer(STATS_PERIOD, self._log_stats)

    # -- parameters ---------------------------------------------------------------------------
    def _apply_parameters(self, parameters: list[Parameter]) -> None:
        r, g, b = self.world.background
        for p in parameters:
            if p.name == 'background_r':
                r = int(p.value)
            elif p.name == 'background_g':
                g = int(p.value)
            elif p.name == 'background_b':
                b = int(p.value)
            elif p.name == 'holonomic':
                self.world.holonomic = bool(p.value)
        self.world.background = (r, g, b)
        self.revision += 1

    def _on_parameter_event(self, event: ParameterEvent) -> None:
        if event.node == self.get_fully_qualified_name():
            self._update_frame()  # turtlesim repaints on its own parameter events

    # -- world services -----------------------------------------------------------------------
    def _spawn(self, name: str, x: float, y: float, theta: float) -> str:
        real_name = self.world.spawn(name, x, y, theta)
        if not real_name:
            return ''
        try:
            self._interfaces[real_name] = _TurtleInterface(self, self.world.turtles[real_name])
        except ValueError as e:  # a name that makes no valid topic: refuse it, stay up
            self.world.kill(real_name)
            self.get_logger().error(f'Cannot spawn turtle [{real_name}]: {e}')
            return ''
        t = self.world.turtles[real_name]
        self.get_logger().info(
            f'Spawning turtle [{real_name}] at x=[{t.x:f}], y=[{t.y:f}], theta=[{t.theta:f}]'
        )
        self.revision += 1
        return real_name

    def finite(self, what: str, **values: float) -> bool:
        """Whether every value is a finite number turtlesim's float32 pose can hold; else
        the request is refused with a log line (NaN or infinity would end the simulation,
        and 1e308 cannot be written into a Pose)."""
        bad = {k: v for k, v in values.items() if not (math.isfinite(v) and abs(v) <= _FLOAT32_MAX)}
        if bad:
            shown = ', '.join(f'{k}={v}' for k, v in bad.items())
            self.get_logger().error(
                f'Ignoring a {what} with a value that is not a finite float32 ({shown})'
            )
        return not bad

    def _on_spawn(self, request: Spawn.Request, response: Spawn.Response) -> Spawn.Response:
        if not self.finite('spawn request', x=request.x, y=request.y, theta=request.theta):
            response.name = ''
            return response
        name = self._spawn(request.name, request.x, request.y, request.theta)
        if not name and request.name in self.world.turtles:
            self.get_logger().error(f'A turtle named [{request.name}] already exists')
        response.name = name
        return response

    def _on_kill(self, request: Kill.Request, response: Kill.Response) -> Kill.Response:
        if not self.world.kill(request.name):
            self.get_logger().error(f'Tried to kill turtle [{request.name}], which does not exist')
            return response
        self._interfaces.pop(request.name).destroy()
        self.revision += 1
        return response

    def _on_clear(self, request: Empty.Request, response: Empty.Response) -> Empty.Response:
        self.get_logger().info('Clearing turtlesim.')
        self.world.clear()
        self.revision += 1
        return response

    def _on_reset(self, request: Empty.Request, response: Empty.Response) -> Empty.Response:
        self.get_logger().info('Resetting turtlesim.')
        for interface in self._interfaces.values():
            interface.destroy()
        self._interfaces.clear()
        self.world.remove_all()
        self._spawn('', sim.WIDTH / 2.0, sim.HEIGHT / 2.0, 0.0)
        self.world.clear()
        self.revision += 1
        return response

    # -- the 16 ms step -----------------------------------------------------------------------
    def step(self) -> None:
        """Advance the world one tick and publish what it did (the timer's callback)."""
        began = time.perf_counter()
        logger = self.get_logger()
        for update in self.world.step():
            interface = self._interfaces.get(update.name)
            if interface is None:
                continue
            for event in update.events:
                if isinstance(event, sim.GoalFeedback):
                    interface.feedback(event.goal, event.remaining)
                elif isinstance(event, sim.GoalDone):
                    if event.outcome == 'canceled':
                        logger.info('Rotation goal canceled')
                    else:
                        logger.info('Rotation goal completed successfully')
                    interface.finish(event.goal, event.outcome)
                elif isinstance(event, sim.WallHit):
                    logger.warn(
                        f'Oh no! I hit the wall! (Clamping from [x={event.x:f}, y={event.y:f}])'
                    )
            interface.publish(update)
        self._update_frame()
        self.step_seconds += time.perf_counter() - began

    def _log_stats(self) -> None:
        """At debug level (`--ros-args --log-level turtlesim:=debug`): step and redraw rates
        and the time a step takes, over the last period."""
        now = time.monotonic()
        t0, steps0, frames0, busy0 = self._last_stats
        self._last_stats = (now, self.world.steps, self.render_frames, self.step_seconds)
        elapsed = now - t0
        steps = self.world.steps - steps0
        if elapsed <= 0 or steps <= 0:
            return
        self.get_logger().debug(
            f'step rate {steps / elapsed:.2f} Hz, render rate '
            f'{(self.render_frames - frames0) / elapsed:.2f} Hz, step time '
            f'{1000 * (self.step_seconds - busy0) / steps:.3f} ms, '
            f'turtles {len(self.world.turtles)}'
        )

    def step_rate(self) -> float:
        """Steps per second of wall time since the node started."""
        t0, s0 = self._started
        elapsed = time.monotonic() - t0
        return (self.world.steps - s0) / elapsed if elapsed > 0 else 0.0

    def _update_frame(self) -> None:
        world = self.world
        self.frame = Frame(
            tuple(
                TurtleView(t.name, t.x, t.y, t.theta, t.sprite)
                for t in (world.turtles[n] for n in sorted(world.turtles))
            ),
            world.background,
            world.steps,
        )
