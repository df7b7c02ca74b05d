"""Joint positions to link frames, against transforms3d (an independent implementation):
revolute, continuous, prismatic, fixed, floating kept at its origin, mimic joints."""

from __future__ import annotations

import math

import numpy as np
import pytest
from transforms3d import affines, axangles, euler, quaternions

from ros2lite.tf2.math import Transform
from ros2lite.urdf import parse_urdf
from ros2lite.urdf.kinematics import joint_transform, link_poses, with_mimics
from tests.urdf.robots import ARM


def matrix(t: Transform) -> np.ndarray:
    (x, y, z), (qx, qy, qz, qw) = t
    return affines.compose(np.array([x, y, z]), quaternions.quat2mat([qw, qx, qy, qz]), np.ones(3))


def expected(xyz: tuple[float, ...], rpy: tuple[float, ...], motion: np.ndarray) -> np.ndarray:
    # URDF's rpy: fixed axes x, then y, then z
    origin = affines.compose(np.array(xyz), euler.euler2mat(*rpy, axes='sxyz'), np.ones(3))
    return origin @ motion


def test_each_joint_type_moves_as_robot_state_publisher_moves_it() -> None:
    robot = parse_urdf(ARM)
    j = robot.joints
    rot = axangles.axangle2aff([0, 1, 0], 0.7)
    assert np.allclose(
        matrix(joint_transform(j['elbow'], 0.7)), expected((0, 0, 0.3), (0, 0, 0), rot)
    )
    wheel = axangles.axangle2aff([0, 0, 1], -2.5)
    got = matrix(joint_transform(j['wheel_joint'], -2.5))
    assert np.allclose(got, expected((0, 0.2, 0), (-math.pi / 2, 0, 0), wheel))
    slide = affines.compose(np.array([0.05, 0, 0]), np.eye(3), np.ones(3))
    assert np.allclose(
        matrix(joint_transform(j['slide'], 0.05)), expected((0.2, 0, 0), (0, 0, 0), slide)
    )
    # fixed and floating joints stay at their origin, whatever position is given
    for name, xyz, rpy in (
        ('base_to_shoulder', (0, 0, 0.1), (0, 0, math.pi / 2)),
        ('camera_mount', (0.1, 0, 0.2), (0, 0.5, 0)),
    ):
        assert np.allclose(matrix(joint_transform(j[name], 3.0)), expected(xyz, rpy, np.eye(4)))


def test_mimic_joints_follow_their_leader_unless_named() -> None:
    robot = parse_urdf(ARM)
    assert with_mimics(robot, {'finger_left_joint': 0.03}) == {
        'finger_left_joint': 0.03,
        'finger_right_joint': -0.03,
    }
    assert with_mimics(robot, {'finger_left_joint': 0.03, 'finger_right_joint': 0.01}) == {
        'finger_left_joint': 0.03,
        'finger_right_joint': 0.01,
    }
    assert with_mimics(robot, {}) == {}


def test_link_poses_chain_the_tree_from_the_root() -> None:
    robot = parse_urdf(ARM)
    poses = link_poses(robot, {'elbow': 0.5, 'slide': 0.1, 'finger_left_joint': 0.02})
    assert set(poses) == set(robot.links)
    shoulder = expected((0, 0, 0.1), (0, 0, math.pi / 2), np.eye(4))
    forearm = shoulder @ expected((0, 0, 0.3), (0, 0, 0), axangles.axangle2aff([0, 1, 0], 0.5))
    slider = forearm @ affines.compose(np.array([0.3, 0, 0]), np.eye(3), np.ones(3))
    right = slider @ affines.compose(np.array([0, -0.02, 0]), np.eye(3), np.ones(3))
    assert np.allclose(matrix(poses['forearm']), forearm)
    assert np.allclose(matrix(poses['finger_right']), right)
    assert poses['base_link'] == ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0))
    # the shoulder's yaw of 90° turns the forearm's x into the base's y
    assert matrix(link_poses(robot)['slider'])[1, 3] == pytest.approx(0.2)
