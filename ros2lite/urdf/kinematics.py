"""Joint positions to frames, as robot_state_publisher computes them: each joint gives the
transform from its parent link's frame to its child's.

A revolute or continuous joint turns about its axis by its position, a prismatic one slides
along it; fixed joints sit at their origin, and so do floating and planar ones (a single
position cannot place them: robot_state_publisher's kinematics treats them as fixed, though
it publishes them with the moving ones). A mimic joint's position is its leader's times the
multiplier plus the offset, unless the joint state names it itself.
"""

from __future__ import annotations

from collections.abc import Mapping
from math import cos, sin

from ros2lite.tf2.math import IDENTITY, Transform, compose, quaternion_from_rpy
from ros2lite.urdf.model import Joint, Robot

__all__ = ['joint_transform', 'link_poses', 'origin', 'with_mimics']


def origin(joint: Joint) -> Transform:
    """The child's frame in the parent's at position 0."""
    return (joint.xyz, quaternion_from_rpy(*joint.rpy))


def joint_transform(joint: Joint, position: float = 0.0) -> Transform:
    """Parent frame -> child frame with the joint at `position` (radians or metres)."""
    if joint.type in ('revolute', 'continuous'):
        half = position * 0.5
        s = sin(half)
        x, y, z = joint.axis
        return compose(origin(joint), ((0.0, 0.0, 0.0), (x * s, y * s, z * s, cos(half))))
    if joint.type == 'prismatic':
        x, y, z = joint.axis
        return compose(origin(joint), ((x * position, y * position, z * position), IDENTITY[1]))
    return origin(joint)


def with_mimics(robot: Robot, positions: Mapping[str, float]) -> dict[str, float]:
    """`positions` plus every mimic joint whose leader (through any chain) has one; a mimic
    joint named in `positions` keeps its own value."""
    result = dict(positions)

    def value(name: str, depth: int) -> float | None:
        if name in result:
            return result[name]
        joint = robot.joints.get(name)
        if joint is None or joint.mimic is None or depth > len(robot.joints):
            return None  # parse_urdf refuses mimic loops; the depth bound guards a hand-made Robot
        leader = value(joint.mimic.joint, depth + 1)
        if leader is None:
            return None
        result[name] = leader * joint.mimic.multiplier + joint.mimic.offset
        return result[name]

    for joint in robot.joints.values():
        if joint.mimic is not None:
            value(joint.name, 0)
    return result


def link_poses(robot: Robot, positions: Mapping[str, float] | None = None) -> dict[str, Transform]:
    """Every link's frame in the root link's, at `positions` (a joint not named is at 0)."""
    known = with_mimics(robot, positions or {})
    poses: dict[str, Transform] = {robot.root: IDENTITY}
    children: dict[str, list[Joint]] = {}
    for joint in robot.joints.values():
        children.setdefault(joint.parent, []).append(joint)
    todo = [robot.root]
    while todo:
        parent = todo.pop()
        for joint in children.get(parent, ()):
            if joint.child in poses:
                continue  # only a hand-made Robot has a loop
            poses[joint.child] = compose(
                poses[parent], joint_transform(joint, known.get(joint.name, 0.0))
            )
            todo.append(joint.child)
    return poses
