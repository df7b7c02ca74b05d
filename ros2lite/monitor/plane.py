"""The floor plane, as a top-down view sees it: 2D affine maps (what a 3D transform does to
points on the floor, seen from above), poses as (x, y, yaw), their composition, and the
robot's outline."""

from __future__ import annotations

import math
from dataclasses import dataclass

from ros2lite.tf2.math import Transform, matrix_from_quaternion

__all__ = [
    'IDENTITY',
    'Affine',
    'Footprint',
    'Point',
    'Pose2',
    'apply',
    'invert',
    'planar',
    'pose_affine',
    'pose_of',
    'then',
    'yaw_of',
]

Point = tuple[float, float]
Pose2 = tuple[float, float, float]  # x, y, yaw
Affine = tuple[float, float, float, float, float, float]  # x' = a x + b y + c, y' = d x + e y + f
IDENTITY: Affine = (1.0, 0.0, 0.0, 0.0, 1.0, 0.0)
CIRCLE_SIDES = 24  # a round footprint is drawn as this polygon


def yaw_of(q: tuple[float, float, float, float]) -> float:
    """The heading (rotation about z) of quaternion (x, y, z, w)."""
    x, y, z, w = q
    return math.atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z))


def planar(t: Transform) -> Affine:
    """The floor-plane part of a 3D transform: where a point (x, y, 0) lands, seen from above."""
    (tx, ty, _), q = t
    (m00, m01, _), (m10, m11, _), _ = matrix_from_quaternion(q)
    return (m00, m01, tx, m10, m11, ty)


def apply(a: Affine, x: float, y: float) -> Point:
    return (a[0] * x + a[1] * y + a[2], a[3] * x + a[4] * y + a[5])


def pose_affine(x: float, y: float, yaw: float) -> Affine:
    c, s = math.cos(yaw), math.sin(yaw)
    return (c, -s, x, s, c, y)


def pose_of(a: Affine) -> Pose2:
    """Where an affine puts the origin, and which way it turns the x axis."""
    return (a[2], a[5], math.atan2(a[3], a[0]))


def then(outer: Affine, inner: Affine) -> Affine:
    """`inner` first, then `outer`."""
    a, b, c, d, e, f = outer
    p, q, r, s, t, u = inner
    return (a * p + b * s, a * q + b * t, a * r + b * u + c, d * p + e * s, d * q + e * t,
            d * r + e * u + f)  # fmt: skip


def invert(m: Affine) -> Affine:
    a, b, c, d, e, f = m
    det = a * e - b * d
    if abs(det) < 1e-12:
        det = 1e-12
    ia, ib, id_, ie = e / det, -b / det, -d / det, a / det
    return (ia, ib, -(ia * c + ib * f), id_, ie, -(id_ * c + ie * f))


@dataclass(frozen=True)
class Footprint:
    """The robot's outline in its base frame: a circle of `radius`, or a box `length` x
    `width`, centred at (x, y) and turned by `yaw`."""

    kind: str = 'circle'
    radius: float = 0.2
    length: float = 0.0
    width: float = 0.0
    x: float = 0.0
    y: float = 0.0
    yaw: float = 0.0

    def outline(self, pose: Pose2) -> list[Point]:
        """The outline's corners in the fixed frame, the robot at `pose` (closed: the first
        point again at the end)."""
        place = then(pose_affine(*pose), pose_affine(self.x, self.y, self.yaw))
        if self.kind == 'box':
            hx, hy = self.length / 2, self.width / 2
            corners = [(hx, hy), (-hx, hy), (-hx, -hy), (hx, -hy)]
        else:
            r = self.radius
            corners = [
                (r * math.cos(2 * math.pi * k / CIRCLE_SIDES),
                 r * math.sin(2 * math.pi * k / CIRCLE_SIDES))
                for k in range(CIRCLE_SIDES)
            ]  # fmt: skip
        points = [apply(place, x, y) for x, y in corners]
        return [*points, points[0]]

    def reach(self) -> float:
        """How far ahead of the base frame the outline ends (where the heading mark points)."""
        if self.kind == 'box':
            return self.x + self.length / 2
        return self.x + self.radius
