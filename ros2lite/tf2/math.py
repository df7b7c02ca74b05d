"""The rigid-transform arithmetic tf2 needs, on plain float tuples.

A quaternion is `(x, y, z, w)`, a vector `(x, y, z)`, a transform `(vector, quaternion)`.
Written out here rather than taken from a library: the whole of it is these few formulas, it
must give the numbers tf2's LinearMath gives (its slerp's short-path rule, its Euler
conventions, its quaternion inverse being the conjugate), and the buffer calls it on every step
of every lookup, where tuples of floats beat array libraries' per-call overhead by far.
"""

from __future__ import annotations

from math import acos, asin, atan2, cos, pi, sin, sqrt

__all__ = [
    'IDENTITY',
    'Quat',
    'Transform',
    'Vec',
    'compose',
    'inverse',
    'lerp',
    'matrix_from_quaternion',
    'qconj',
    'qmul',
    'quaternion_from_rpy',
    'rotate',
    'rpy_from_matrix',
    'rpy_from_quaternion',
    'slerp',
]

Vec = tuple[float, float, float]
Quat = tuple[float, float, float, float]
Transform = tuple[Vec, Quat]
Matrix = tuple[Vec, Vec, Vec]

IDENTITY: Transform = ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0))


def qmul(a: Quat, b: Quat) -> Quat:
    """The Hamilton product `a * b` (apply b, then a)."""
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return (
        aw * bx + ax * bw + ay * bz - az * by,
        aw * by + ay * bw + az * bx - ax * bz,
        aw * bz + az * bw + ax * by - ay * bx,
        aw * bw - ax * bx - ay * by - az * bz,
    )


def qconj(q: Quat) -> Quat:
    """The conjugate, which tf2 uses as the inverse (its quaternions are unit ones)."""
    return (-q[0], -q[1], -q[2], q[3])


def rotate(q: Quat, v: Vec) -> Vec:
    """`v` rotated by `q`, as the product q * v * conj(q) (tf2's quatRotate)."""
    qx, qy, qz, qw = q
    vx, vy, vz = v
    # p = q * (v, 0)
    px = qw * vx + qy * vz - qz * vy
    py = qw * vy + qz * vx - qx * vz
    pz = qw * vz + qx * vy - qy * vx
    pw = -qx * vx - qy * vy - qz * vz
    # p * conj(q), vector part
    return (
        -pw * qx + px * qw - py * qz + pz * qy,
        -pw * qy + py * qw - pz * qx + px * qz,
        -pw * qz + pz * qw - px * qy + py * qx,
    )


def compose(a: Transform, b: Transform) -> Transform:
    """`a * b`: first b, then a (a point in b's child frame lands in a's parent frame)."""
    (ax, ay, az), aq = a
    rx, ry, rz = rotate(aq, b[0])
    return ((rx + ax, ry + ay, rz + az), qmul(aq, b[1]))


def inverse(t: Transform) -> Transform:
    """The transform that undoes `t`."""
    inv_q = qconj(t[1])
    x, y, z = rotate(inv_q, t[0])
    return ((-x, -y, -z), inv_q)


def lerp(a: Vec, b: Vec, ratio: float) -> Vec:
    """The point `ratio` of the way from a to b."""
    return (
        a[0] + (b[0] - a[0]) * ratio,
        a[1] + (b[1] - a[1]) * ratio,
        a[2] + (b[2] - a[2]) * ratio,
    )


def slerp(a: Quat, b: Quat, ratio: float) -> Quat:
    """Spherical interpolation along the shorter arc, with tf2's formula (so a and -b, the
    same rotation, interpolate the same way as a and b)."""
    dot = a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3]
    norms = sqrt(
        (a[0] ** 2 + a[1] ** 2 + a[2] ** 2 + a[3] ** 2)
        * (b[0] ** 2 + b[1] ** 2 + b[2] ** 2 + b[3] ** 2)
    )
    cosine = abs(dot) / norms
    theta = acos(cosine if cosine < 1.0 else 1.0)  # half the angle between the rotations
    if theta == 0.0:
        return a
    d = 1.0 / sin(theta)
    s0 = sin((1.0 - ratio) * theta) * d
    s1 = sin(ratio * theta) * d
    if dot < 0:
        s1 = -s1
    return (
        a[0] * s0 + b[0] * s1,
        a[1] * s0 + b[1] * s1,
        a[2] * s0 + b[2] * s1,
        a[3] * s0 + b[3] * s1,
    )


def quaternion_from_rpy(roll: float, pitch: float, yaw: float) -> Quat:
    """Fixed-axis roll (x), pitch (y), yaw (z) in radians, as tf2's Quaternion.setRPY."""
    cr, sr = cos(roll * 0.5), sin(roll * 0.5)
    cp, sp = cos(pitch * 0.5), sin(pitch * 0.5)
    cy, sy = cos(yaw * 0.5), sin(yaw * 0.5)
    return (
        sr * cp * cy - cr * sp * sy,
        cr * sp * cy + sr * cp * sy,
        cr * cp * sy - sr * sp * cy,
        cr * cp * cy + sr * sp * sy,
    )


def matrix_from_quaternion(q: Quat) -> Matrix:
    """The 3x3 rotation matrix, rows first (tf2's Matrix3x3 from a quaternion: scaled by the
    quaternion's squared length, so a slightly long one still gives a rotation)."""
    x, y, z, w = q
    s = 2.0 / (x * x + y * y + z * z + w * w)
    xs, ys, zs = x * s, y * s, z * s
    wx, wy, wz = w * xs, w * ys, w * zs
    xx, xy, xz = x * xs, x * ys, x * zs
    yy, yz, zz = y * ys, y * zs, z * zs
    return (
        (1.0 - (yy + zz), xy - wz, xz + wy),
        (xy + wz, 1.0 - (xx + zz), yz - wx),
        (xz - wy, yz + wx, 1.0 - (xx + yy)),
    )


def rpy_from_matrix(m: Matrix) -> Vec:
    """(roll, pitch, yaw) of a rotation matrix, pitch in [-pi/2, pi/2] (tf2's getEulerYPR,
    first solution; at the gimbal lock yaw is 0)."""
    m20 = m[2][0]
    if abs(m20) >= 1.0:
        roll = atan2(m[2][1], m[2][2])
        return (roll, pi / 2.0 if m20 < 0 else -pi / 2.0, 0.0)
    pitch = -asin(m20)
    c = cos(pitch)
    roll = atan2(m[2][1] / c, m[2][2] / c)
    yaw = atan2(m[1][0] / c, m[0][0] / c)
    return (roll, pitch, yaw)


def rpy_from_quaternion(q: Quat) -> Vec:
    """(roll, pitch, yaw) of a quaternion, as tf2_echo computes them."""
    return rpy_from_matrix(matrix_from_quaternion(q))
