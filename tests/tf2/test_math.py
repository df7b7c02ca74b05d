"""ros2lite.tf2.math against transforms3d (an independent implementation) and tf2's own
conventions (its slerp's short path, its Euler angles)."""

from __future__ import annotations

import math
import random

import numpy as np
from transforms3d import affines, euler, quaternions

from ros2lite.tf2 import math as tfm

RNG = random.Random(27)


def unit_quat() -> tfm.Quat:
    while True:
        q = [RNG.gauss(0, 1) for _ in range(4)]
        n = math.sqrt(sum(v * v for v in q))
        if n > 1e-3:
            return (q[0] / n, q[1] / n, q[2] / n, q[3] / n)


def wxyz(q: tfm.Quat) -> np.ndarray:
    return np.array([q[3], q[0], q[1], q[2]])


def matrix(t: tfm.Transform) -> np.ndarray:
    return affines.compose(np.array(t[0]), quaternions.quat2mat(wxyz(t[1])), np.ones(3))


def vec() -> tfm.Vec:
    return (RNG.uniform(-5, 5), RNG.uniform(-5, 5), RNG.uniform(-5, 5))


def test_compose_inverse_rotate_agree_with_matrices() -> None:
    for _ in range(200):
        a, b = (vec(), unit_quat()), (vec(), unit_quat())
        assert np.allclose(matrix(tfm.compose(a, b)), matrix(a) @ matrix(b), atol=1e-12)
        assert np.allclose(matrix(tfm.inverse(a)), np.linalg.inv(matrix(a)), atol=1e-12)
        v = vec()
        assert np.allclose(tfm.rotate(a[1], v), quaternions.rotate_vector(v, wxyz(a[1])))
        assert np.allclose(tfm.matrix_from_quaternion(a[1]), quaternions.quat2mat(wxyz(a[1])))


def test_slerp_follows_the_shorter_arc_at_constant_speed() -> None:
    for _ in range(200):
        a, b = unit_quat(), unit_quat()
        ratio = RNG.random()
        got = tfm.slerp(a, b, ratio)
        # the oracle: a * exp(ratio * log(a^-1 b)), with b flipped onto a's hemisphere
        bb = wxyz(b) if np.dot(wxyz(a), wxyz(b)) >= 0 else -wxyz(b)
        axis, angle = quaternions.quat2axangle(quaternions.qmult(quaternions.qinverse(wxyz(a)), bb))
        want = quaternions.qmult(wxyz(a), quaternions.axangle2quat(axis, angle * ratio))
        assert np.allclose(quaternions.quat2mat(wxyz(got)), quaternions.quat2mat(want), atol=1e-12)
        assert abs(sum(v * v for v in got) - 1) < 1e-12
    q = unit_quat()
    assert tfm.slerp(q, q, 0.3) == q
    assert tfm.slerp(q, tuple(-v for v in q), 0.5) == q  # the same rotation: no motion


def test_rpy_round_trip_and_conventions() -> None:
    for _ in range(200):
        roll, pitch, yaw = RNG.uniform(-3, 3), RNG.uniform(-1.5, 1.5), RNG.uniform(-3, 3)
        q = tfm.quaternion_from_rpy(roll, pitch, yaw)
        # static x, then y, then z axes: transforms3d's 'sxyz'
        assert np.allclose(quaternions.quat2mat(wxyz(q)), euler.euler2mat(roll, pitch, yaw, 'sxyz'))
        assert np.allclose(tfm.rpy_from_quaternion(q), (roll, pitch, yaw), atol=1e-9)
    # at the gimbal lock (tf2's branch for |m20| >= 1) pitch is exactly +-pi/2 and yaw 0
    c, s = math.cos(0.3), math.sin(0.3)
    down = ((0.0, s, c), (0.0, c, -s), (-1.0, 0.0, 0.0))
    assert tfm.rpy_from_matrix(down) == (math.atan2(0.0, 0.0), math.pi / 2, 0.0)
    up = ((0.0, 0.0, -1.0), (0.0, 1.0, 0.0), (1.0, 0.0, 0.0))
    assert tfm.rpy_from_matrix(up) == (0.0, -math.pi / 2, 0.0)
