"""`joint_state_publisher`: the node of that name, as joint_state_publisher's own.

The robot comes from a URDF file named on the command line, else from `/robot_description`
(transient local, so a robot_state_publisher started before or after is heard; a new
description rebuilds the joints). Every revolute, continuous and prismatic joint is published
on `/joint_states` at `rate` Hz, in the description's order: a free joint at its default
(0, or the middle of a range that excludes 0, or its `zeros.<joint>` parameter) until a
JointState on one of the `source_list` topics sets it; a mimic joint (`use_mimic_tags`) or
one named in `dependent_joints.<joint>.{parent,factor,offset}` follows its parent. Continuous
joints range over [-pi, pi]; `delta` (rad per update) sweeps the free joints over their ranges.

`FreeJoint` and `JointStates` are the model `joint_state_publisher_gui`'s sliders move.
"""

from __future__ import annotations

import math
import sys
import threading
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

from ros2lite.bundled.display import own_arguments
from ros2lite.bundled.runner import run_node
from ros2lite.exceptions import ParameterUninitializedException
from ros2lite.msgs.sensor_msgs.msg import JointState
from ros2lite.msgs.std_msgs.msg import String
from ros2lite.node import Node
from ros2lite.parameter import Parameter
from ros2lite.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy
from ros2lite.urdf import Robot, UrdfError, parse_urdf

__all__ = ['FreeJoint', 'JointStatePublisher', 'JointStates', 'main']

DESCRIPTION_QOS = QoSProfile(
    depth=1, reliability=ReliabilityPolicy.RELIABLE, durability=DurabilityPolicy.TRANSIENT_LOCAL
)


@dataclass
class FreeJoint:
    """A joint nothing else drives: its range, its default and where it is now."""

    name: str
    lower: float
    upper: float
    zero: float
    continuous: bool = False
    position: float = 0.0
    velocity: float | None = None
    effort: float | None = None
    forward: bool = True  # the sweep's direction, with `delta`


@dataclass
class Dependent:
    """A joint that follows another: position = parent's * factor + offset."""

    parent: str
    factor: float = 1.0
    offset: float = 0.0


@dataclass
class JointStates:
    """The joints of one robot as joint_state_publisher treats them."""

    names: list[str] = field(default_factory=list)  # every published joint, in order
    free: dict[str, FreeJoint] = field(default_factory=dict)
    dependent: dict[str, Dependent] = field(default_factory=dict)

    @classmethod
    def of(
        cls,
        robot: Robot,
        *,
        zeros: dict[str, float] | None = None,
        dependent: dict[str, Dependent] | None = None,
        use_mimic_tags: bool = True,
        default_velocity: bool = False,
        default_effort: bool = False,
    ) -> JointStates:
        """The joints of `robot`, with the node's parameters applied."""
        zeros = zeros or {}
        out = cls(dependent=dict(dependent or {}))
        for joint in robot.joints.values():
            if not joint.moving:
                continue  # fixed, floating and planar joints have no single position
            out.names.append(joint.name)
            if joint.name in out.dependent:
                continue
            if use_mimic_tags and joint.mimic is not None:
                mimic = joint.mimic
                out.dependent[joint.name] = Dependent(mimic.joint, mimic.multiplier, mimic.offset)
                continue
            if joint.type == 'continuous':
                lower, upper = -math.pi, math.pi
            else:
                lower, upper = joint.lower, joint.upper
            if joint.name in zeros:
                zero = zeros[joint.name]
            elif lower > 0 or upper < 0:
                zero = (lower + upper) / 2
            else:
                zero = 0.0
            out.free[joint.name] = FreeJoint(
                joint.name,
                lower,
                upper,
                zero,
                continuous=joint.type == 'continuous',
                position=zero,
                velocity=0.0 if default_velocity else None,
                effort=0.0 if default_effort else None,
            )
        return out

    def leader(self, name: str) -> tuple[FreeJoint, float, float] | None:
        """The free joint `name` follows (through any chain), with the chain's factor and
        offset; None when the chain ends nowhere or loops."""
        factor, offset = 1.0, 0.0
        seen = {name}
        while name in self.dependent:
            dep = self.dependent[name]
            offset += factor * dep.offset
            factor *= dep.factor
            name = dep.parent
            if name in seen:
                return None
            seen.add(name)
        joint = self.free.get(name)
        return None if joint is None else (joint, factor, offset)

    def message(self, publish_positions: bool = True) -> JointState:
        """The joint state of every joint (stamp left to the caller)."""
        msg = JointState()
        rows = [(name, self.leader(name)) for name in self.names]
        rows = [(name, found) for name, found in rows if found is not None]
        with_velocity = any(found[0].velocity is not None for _, found in rows if found)
        with_effort = any(found[0].effort is not None for _, found in rows if found)
        for name, found in rows:
            assert found is not None
            joint, factor, offset = found
            msg.name.append(name)
            if publish_positions:
                msg.position.append(joint.position * factor + offset)
            if with_velocity:
                msg.velocity.append((joint.velocity or 0.0) * factor)
            if with_effort:
                msg.effort.append(joint.effort or 0.0)
        return msg

    def sweep(self, delta: float) -> None:
        """Move every free joint `delta` along its range, turning at the ends."""
        for joint in self.free.values():
            step = delta if joint.forward else -delta
            joint.position += step
            if joint.position > joint.upper:
                joint.position, joint.forward = joint.upper, False
            elif joint.position < joint.lower:
                joint.position, joint.forward = joint.lower, True


class JointStatePublisher(Node):
    """Publishes the joint states of the robot it reads; `joints` under `lock` is the model
    (a GUI moves its free joints, `on_robot` hears of a new robot)."""

    def __init__(self, urdf_file: str | None = None) -> None:
        super().__init__(
            'joint_state_publisher', automatically_declare_parameters_from_overrides=True
        )
        self.lock = threading.Lock()
        self.joints = JointStates()
        self.robot: Robot | None = None
        # called with the new model when the robot changes (on the executor's thread)
        self.on_robot: list[Callable[[JointStates], None]] = []

        def param(name: str, default: bool | int | float | str | list[str]) -> object:
            if not self.has_parameter(name):
                self.declare_parameter(name, default)
            return self.get_parameter(name).value

        self.publish_positions = bool(param('publish_default_positions', True))
        self.default_velocity = bool(param('publish_default_velocities', False))
        self.default_effort = bool(param('publish_default_efforts', False))
        self.use_mimic_tags = bool(param('use_mimic_tags', True))
        param('use_smallest_joint_limits', True)  # safety limits: not read from the URDF
        delta = param('delta', 0.0)
        self.delta = float(delta) if isinstance(delta, (int, float)) else 0.0
        rate = param('rate', 10)
        if not isinstance(rate, (int, float)) or rate <= 0:
            raise ValueError(f'rate must be a positive number, not {rate!r}')
        if not self.has_parameter('source_list'):  # a string array, empty by default
            self.declare_parameter('source_list', Parameter.Type.STRING_ARRAY)
        try:
            sources = self.get_parameter('source_list').value
        except ParameterUninitializedException:
            sources = []
        self.zeros = {
            name: float(p.value)
            for name, p in self.get_parameters_by_prefix('zeros').items()
            if isinstance(p.value, (int, float))
        }
        self.dependents = _dependents(self)
        self.pub = self.create_publisher(JointState, 'joint_states', 10)
        for topic in sources if isinstance(sources, list) else []:
            if topic:
                self.create_subscription(JointState, str(topic), self._on_source, 10)
        if urdf_file is not None:
            try:
                text = Path(urdf_file).read_text(encoding='utf-8')
            except OSError as e:
                raise ValueError(f'cannot read {urdf_file}: {e.strerror}') from None
            self.set_robot(parse_urdf(text))
        else:
            self.create_subscription(
                String, 'robot_description', self._on_description, DESCRIPTION_QOS
            )
        self.timer = self.create_timer(1.0 / float(rate), self._publish)

    def set_robot(self, robot: Robot) -> None:
        """Take `robot`'s joints (positions back at their defaults) and tell the listeners."""
        joints = JointStates.of(
            robot,
            zeros=self.zeros,
            dependent=self.dependents,
            use_mimic_tags=self.use_mimic_tags,
            default_velocity=self.default_velocity,
            default_effort=self.default_effort,
        )
        with self.lock:
            self.robot, self.joints = robot, joints
        for callback in self.on_robot:
            callback(joints)

    def _on_description(self, msg: String) -> None:
        try:
            robot = parse_urdf(msg.data)
        except UrdfError as e:
            self.get_logger().error(f'robot_description: {e}')
            return
        self.set_robot(robot)

    def _on_source(self, msg: JointState) -> None:
        with self.lock:
            for i, name in enumerate(msg.name):
                joint = self.joints.free.get(name)
                if joint is None:
                    continue
                if i < len(msg.position):
                    joint.position = msg.position[i]
                if i < len(msg.velocity):
                    joint.velocity = msg.velocity[i]
                if i < len(msg.effort):
                    joint.effort = msg.effort[i]

    def _publish(self) -> None:
        with self.lock:
            if self.robot is None:
                return  # nothing to say until a robot is known
            if self.delta > 0:
                self.joints.sweep(self.delta)
            msg = self.joints.message(self.publish_positions)
        msg.header.stamp = self.get_clock().now().to_msg()
        self.pub.publish(msg)


def _dependents(node: Node) -> dict[str, Dependent]:
    """`dependent_joints.<joint>.{parent,factor,offset}` parameters."""
    found: dict[str, dict[str, object]] = {}
    for key, p in node.get_parameters_by_prefix('dependent_joints').items():
        joint, _, field_name = key.rpartition('.')
        if joint:
            found.setdefault(joint, {})[field_name] = p.value
    out = {}
    for joint, fields in found.items():
        parent = fields.get('parent')
        if isinstance(parent, str) and parent:
            factor, offset = fields.get('factor', 1.0), fields.get('offset', 0.0)
            out[joint] = Dependent(
                parent,
                float(factor) if isinstance(factor, (int, float)) else 1.0,
                float(offset) if isinstance(offset, (int, float)) else 0.0,
            )
    return out


def urdf_argument(args: list[str] | None) -> str | None:
    """The URDF file named on the command line (the first argument that is not a ROS one)."""
    own = own_arguments(args)
    return own[0] if own else None


def main(args: list[str] | None = None) -> int:
    """`joint_state_publisher [urdf_file]`'s entry point."""
    urdf_file = urdf_argument(args)
    return run_node(lambda: JointStatePublisher(urdf_file), args)


if __name__ == '__main__':
    sys.exit(main())
