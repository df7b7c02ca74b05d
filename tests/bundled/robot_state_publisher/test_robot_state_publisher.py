"""robot_state_publisher as a process on a real router: the description latched on
/robot_description, fixed joints on /tf_static, moving and mimic joints from /joint_states on
/tf (a tf2 Buffer sees the links move), the description changed at run time, and the one-line
refusals."""

from __future__ import annotations

import math
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest
import yaml

from ros2lite.bundled.robot_state_publisher.robot_state_publisher import RobotStatePublisher
from ros2lite.executors import SingleThreadedExecutor
from ros2lite.msgs.sensor_msgs.msg import JointState
from ros2lite.msgs.std_msgs.msg import String
from ros2lite.node import Node
from ros2lite.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy
from ros2lite.tf2 import Buffer, TransformListener
from ros2lite.time import Time
from ros2lite.urdf import parse_urdf
from ros2lite.urdf.kinematics import link_poses
from tests.spinning import spin_until, wait_until
from tests.urdf.robots import ARM

LATCHED = QoSProfile(
    depth=1, reliability=ReliabilityPolicy.RELIABLE, durability=DurabilityPolicy.TRANSIENT_LOCAL
)
# one line: `param set` takes the value as YAML
MOVED_SHOULDER = ARM.replace(
    '<origin xyz="0 0 0.1" rpy="0 0 1.5707963267948966"/>', '<origin xyz="0 0 0.5"/>'
)


def params_file(tmp_path: Path, **params: object) -> Path:
    path = tmp_path / 'rsp.yaml'
    path.write_text(yaml.safe_dump({'robot_state_publisher': {'ros__parameters': params}}))
    return path


def run_rsp(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [
            sys.executable,
            '-m',
            'ros2lite',
            'run',
            'robot_state_publisher',
            'robot_state_publisher',
            *args,
        ],
        capture_output=True,
        text=True,
        timeout=60,
    )


def errors(done: subprocess.CompletedProcess[str]) -> list[str]:
    return [line for line in done.stderr.splitlines() if not line.startswith('[ros2run]')]


def lookup(buffer: Buffer, target: str, source: str) -> tuple[tuple[float, ...], tuple[float, ...]]:
    t = buffer.lookup_transform(target, source, Time()).transform
    return (
        (t.translation.x, t.translation.y, t.translation.z),
        (t.rotation.x, t.rotation.y, t.rotation.z, t.rotation.w),
    )


def close(a: tuple[tuple[float, ...], tuple[float, ...]], b: Any) -> bool:
    return all(
        math.isclose(x, y, abs_tol=1e-9) for x, y in zip(a[0] + a[1], b[0] + b[1], strict=True)
    )


def test_frames_follow_joint_states_and_the_description(
    processes: Any, ros_context: Any, tmp_path: Path
) -> None:
    rsp = processes.cli(
        'run', 'robot_state_publisher', 'robot_state_publisher', '--ros-args',
        '--params-file', str(params_file(tmp_path, robot_description=ARM, frame_prefix='r1/')),
    )  # fmt: skip
    node = Node('rsp_probe', context=ros_context)
    descriptions: list[str] = []
    node.create_subscription(
        String, '/robot_description', lambda m: descriptions.append(m.data), LATCHED
    )
    buffer = Buffer(node=node)
    listener = TransformListener(buffer, node)
    states = node.create_publisher(JointState, '/joint_states', 10)
    executor = SingleThreadedExecutor(context=ros_context)
    executor.add_node(node)
    try:
        # latched: whenever the probe joined, the description and the fixed frames reach it
        spin_until(executor, lambda: descriptions, timeout=20)
        assert descriptions == [ARM]
        # the real one's node name and QoS, as the graph shows them
        (pub,) = wait_until(lambda: node.get_publishers_info_by_topic('/robot_description'))
        assert (pub.node_name, pub.qos_profile.durability, pub.qos_profile.reliability) == (
            'robot_state_publisher',
            DurabilityPolicy.TRANSIENT_LOCAL,
            ReliabilityPolicy.RELIABLE,
        )
        (sub,) = wait_until(lambda: node.get_subscriptions_info_by_topic('/joint_states'))
        assert sub.qos_profile.reliability == ReliabilityPolicy.BEST_EFFORT
        robot = parse_urdf(ARM)
        at_zero = link_poses(robot)
        spin_until(executor, lambda: buffer.can_transform('r1/base_link', 'r1/shoulder', Time()))
        assert close(lookup(buffer, 'r1/base_link', 'r1/shoulder'), at_zero['shoulder'])
        assert not buffer.can_transform('r1/base_link', 'r1/camera', Time())  # floating: never

        def send(positions: dict[str, float]) -> None:
            msg = JointState(name=list(positions), position=list(positions.values()))
            msg.header.stamp = node.get_clock().now().to_msg()
            states.publish(msg)
            executor.spin_once(timeout_sec=0.05)

        first = {'elbow': 0.7, 'slide': 0.05, 'finger_left_joint': 0.03, 'wheel_joint': 1.0}
        want = link_poses(robot, first)
        # finger_right_joint is not sent: only its mimic of finger_left_joint places it

        def arrived(positions: dict[str, float], link: str) -> bool:
            poses = link_poses(robot, positions)
            return buffer.can_transform('r1/base_link', f'r1/{link}', Time()) and close(
                lookup(buffer, 'r1/base_link', f'r1/{link}'), poses[link]
            )

        # /tf is volatile: the state is sent again until the frames have come back
        wait_until(lambda: arrived(first, 'finger_right'), timeout=20, step=lambda: send(first))
        for link in ('forearm', 'slider', 'finger_left', 'finger_right', 'wheel'):
            assert close(lookup(buffer, 'r1/base_link', f'r1/{link}'), want[link]), link
        second = {**first, 'elbow': -0.5}
        wait_until(lambda: arrived(second, 'forearm'), timeout=10, step=lambda: send(second))
        assert not close(lookup(buffer, 'r1/base_link', 'r1/forearm'), want['forearm'])

        # a new description at run time: published again, its fixed frames sent again
        done = subprocess.run(
            [sys.executable, '-m', 'ros2lite', 'param', 'set', '/robot_state_publisher',
             'robot_description', MOVED_SHOULDER.replace('\n', ' ')],
            capture_output=True, text=True, timeout=60,
        )  # fmt: skip
        assert done.returncode == 0, done.stderr
        spin_until(executor, lambda: len(descriptions) == 2, timeout=10)
        moved = link_poses(parse_urdf(descriptions[1]))['shoulder']
        assert moved[0] == (0.0, 0.0, 0.5)
        spin_until(
            executor,
            lambda: close(lookup(buffer, 'r1/base_link', 'r1/shoulder'), moved),
            timeout=10,
        )
        refused = subprocess.run(
            [sys.executable, '-m', 'ros2lite', 'param', 'set', '/robot_state_publisher',
             'robot_description', '<robot name="x"/>'],
            capture_output=True, text=True, timeout=60,
        )  # fmt: skip
        assert "Robot 'x' has no links" in refused.stdout + refused.stderr
        assert len(descriptions) == 2
    finally:
        listener.unregister()
        executor.shutdown()
        node.destroy_node()
    _, err = processes.stop(rsp)
    assert 'Robot initialized' in err


def test_bad_descriptions_are_one_line(ros_context: Any, tmp_path: Path) -> None:
    with pytest.raises(ValueError, match=r'^robot_description parameter must not be empty$'):
        RobotStatePublisher(context=ros_context)
    # as a process: the one line, status 1, no traceback
    broken = run_rsp(
        '--ros-args', '--params-file', str(params_file(tmp_path, robot_description='<robot'))
    )
    assert broken.returncode == 1
    assert len(errors(broken)) == 1
    assert errors(broken)[0].startswith(
        'Unable to initialize the robot from robot_description: '
        'The robot description is not well-formed XML'
    )
    assert 'Traceback' not in broken.stderr
