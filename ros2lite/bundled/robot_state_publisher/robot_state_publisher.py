"""`robot_state_publisher`: the node of that name, with robot_state_publisher's parameters,
topics and QoS, so launch files written for the real one work unchanged.

- `robot_description` (string, required): the URDF (xacro already run). Setting it at run time
  re-reads the robot (a description that does not parse is refused, the old one kept),
  publishes it again and sends the new fixed frames.
- `publish_frequency` (double, 20.0, within (0, 1000]): a joint's frame is sent again at most
  this often, judged by the joint states' stamps, unless `ignore_timestamp` (bool, false).
- `frame_prefix` (string, ""): put before every frame name sent.

Publishes `/robot_description` (std_msgs/String, reliable, transient local, depth 1), the
fixed joints (and planar ones, which the real one's kinematics turns into fixed) once on
`/tf_static`, and for each `/joint_states` message (sensor-data QoS) the frames of the moving
joints it names, mimic joints included, on `/tf` at the message's stamp. Floating joints are
never sent, as the real one skips them.
"""

from __future__ import annotations

import sys
from collections.abc import Sequence

from ros2lite.bundled.runner import run_node
from ros2lite.context import Context
from ros2lite.msgs.geometry_msgs.msg import TransformStamped
from ros2lite.msgs.rcl_interfaces.msg import SetParametersResult
from ros2lite.msgs.sensor_msgs.msg import JointState
from ros2lite.msgs.std_msgs.msg import String
from ros2lite.node import Node
from ros2lite.parameter import Parameter
from ros2lite.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy, qos_profile_sensor_data
from ros2lite.qos_overriding_options import QoSOverridingOptions
from ros2lite.tf2 import StaticTransformBroadcaster, TransformBroadcaster
from ros2lite.tf2.math import Transform
from ros2lite.urdf import Joint, Robot, UrdfError, parse_urdf
from ros2lite.urdf.kinematics import joint_transform, with_mimics

__all__ = ['RobotStatePublisher', 'main']

DESCRIPTION_QOS = QoSProfile(
    depth=1, reliability=ReliabilityPolicy.RELIABLE, durability=DurabilityPolicy.TRANSIENT_LOCAL
)
FIXED_TYPES = ('fixed', 'planar')  # planar: a fixed joint to the real one's kinematics


def _valid_frequency(value: float) -> bool:
    return 0.0 < value <= 1000.0


class RobotStatePublisher(Node):
    """Sends a robot's frames; the description may change while it runs."""

    def __init__(self, *, context: Context | None = None) -> None:
        super().__init__('robot_state_publisher', context=context)
        description = str(self.declare_parameter('robot_description', '').value or '')
        if not description:
            raise ValueError('robot_description parameter must not be empty')
        self._description_pub = self.create_publisher(String, 'robot_description', DESCRIPTION_QOS)
        self.robot = self._parse(description)
        self._moving: dict[str, Joint] = {}
        self._checked: tuple[str, Robot] | None = None  # the description the check parsed
        self._setup(self.robot, description)
        self.publish_frequency = float(self.declare_parameter('publish_frequency', 20.0).value)
        if not _valid_frequency(self.publish_frequency):
            raise ValueError('publish_frequency must be between 0 (exclusive) and 1000')
        self.frame_prefix = str(self.declare_parameter('frame_prefix', '').value)
        self.ignore_timestamp = bool(self.declare_parameter('ignore_timestamp', False).value)
        self._tf = TransformBroadcaster(self)
        self._tf_static = StaticTransformBroadcaster(self)
        self._last_sent: dict[str, int] = {}  # joint -> stamp (ns) of its last frame sent
        self._last_callback = 0
        self.create_subscription(
            JointState,
            'joint_states',
            self._on_joint_states,
            qos_profile_sensor_data,
            qos_overriding_options=QoSOverridingOptions.with_default_policies(),
        )
        self.publish_fixed_transforms()
        # only now: declaring the parameters above is no change to apply
        self.add_on_set_parameters_callback(self._check_parameters)
        self.add_post_set_parameters_callback(self._apply_parameters)

    @staticmethod
    def _parse(description: str) -> Robot:
        try:
            return parse_urdf(description)
        except UrdfError as e:
            raise UrdfError(f'Unable to initialize the robot from robot_description: {e}') from None

    def _setup(self, robot: Robot, description: str) -> None:
        self.robot = robot
        self._moving = {name: j for name, j in robot.joints.items() if j.moving}
        self._description_pub.publish(String(data=description))
        self.get_logger().info('Robot initialized')

    # -- parameters -----------------------------------------------------------------------------
    def _check_parameters(self, parameters: Sequence[Parameter]) -> SetParametersResult:
        for p in parameters:
            if p.name == 'robot_description':
                text = p.value if isinstance(p.value, str) else ''
                if not text:
                    return SetParametersResult(successful=False, reason='Empty URDF is not allowed')
                try:
                    self._checked = (text, self._parse(text))  # applied next: parsed once
                except UrdfError as e:
                    self.get_logger().warning(str(e))
                    return SetParametersResult(successful=False, reason=str(e))
            elif p.name == 'publish_frequency':
                value = p.value
                if not isinstance(value, float) or not _valid_frequency(value):
                    return SetParametersResult(
                        successful=False,
                        reason='publish_frequency must be between 0.0 (exclusive) and 1000.0',
                    )
        return SetParametersResult(successful=True)

    def _apply_parameters(self, parameters: Sequence[Parameter]) -> None:
        for p in parameters:
            if p.name == 'robot_description' and isinstance(p.value, str):
                checked, self._checked = self._checked, None
                robot = checked[1] if checked and checked[0] == p.value else self._parse(p.value)
                self._setup(robot, p.value)
                self.publish_fixed_transforms()
            elif p.name == 'publish_frequency' and isinstance(p.value, float):
                self.publish_frequency = p.value
            elif p.name == 'frame_prefix' and isinstance(p.value, str):
                self.frame_prefix = p.value
            elif p.name == 'ignore_timestamp' and isinstance(p.value, bool):
                self.ignore_timestamp = p.value

    # -- frames ---------------------------------------------------------------------------------
    def _stamped(
        self, joint: Joint, transform: Transform, sec: int, nanosec: int
    ) -> TransformStamped:
        t = TransformStamped()
        t.header.stamp.sec, t.header.stamp.nanosec = sec, nanosec
        t.header.frame_id = self.frame_prefix + joint.parent
        t.child_frame_id = self.frame_prefix + joint.child
        (t.transform.translation.x, t.transform.translation.y, t.transform.translation.z) = (
            transform[0]
        )
        rot = t.transform.rotation
        rot.x, rot.y, rot.z, rot.w = transform[1]
        return t

    def publish_fixed_transforms(self) -> None:
        """Send the fixed joints' frames on `/tf_static` (latched)."""
        sec, nanosec = divmod(self.get_clock().now().nanoseconds, 1_000_000_000)
        fixed = [
            self._stamped(j, joint_transform(j), sec, nanosec)
            for j in self.robot.joints.values()
            if j.type in FIXED_TYPES
        ]
        self._tf_static.sendTransform(fixed)

    def _on_joint_states(self, state: JointState) -> None:
        if len(state.name) != len(state.position):
            if not state.position and state.name:
                self.get_logger().warning(
                    'Robot state publisher ignored a JointState message about joint(s) '
                    f'"{state.name[0]}"(,...) whose position member was empty.'
                )
            else:
                self.get_logger().error(
                    'Robot state publisher ignored an invalid JointState message'
                )
            return
        now = self.get_clock().now().nanoseconds
        if self._last_callback > now:
            self.get_logger().warning('Moved backwards in time, re-publishing joint transforms!')
            self._last_sent.clear()
        self._last_callback = now
        stamp = state.header.stamp.sec * 1_000_000_000 + state.header.stamp.nanosec
        last = min((self._last_sent.get(name, 0) for name in state.name), default=now)
        interval = int(1000.0 / self.publish_frequency) * 1_000_000  # whole ms, as the real one
        if not self.ignore_timestamp and stamp < min(last, now) + interval:
            return
        positions = with_mimics(self.robot, dict(zip(state.name, state.position, strict=True)))
        sec, nanosec = state.header.stamp.sec, state.header.stamp.nanosec
        frames = [
            self._stamped(
                self._moving[name], joint_transform(self._moving[name], value), sec, nanosec
            )
            for name, value in positions.items()
            if name in self._moving
        ]
        self._tf.sendTransform(frames)
        for name in state.name:
            self._last_sent[name] = stamp


def main(args: list[str] | None = None) -> int:
    """`robot_state_publisher`'s entry point."""
    return run_node(RobotStatePublisher, args)


if __name__ == '__main__':
    sys.exit(main())
