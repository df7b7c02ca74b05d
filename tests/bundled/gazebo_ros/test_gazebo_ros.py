"""The spawn entry points on real routers: a workspace robot's URDF (gazebo_ros diff-drive and
ray-sensor tags, its own command topic and laser rate) spawned by `spawn_entity.py` into an
empty 2D world drives from that topic and scans at that rate; `ros_gz_sim create` reads the
description from the topic robot_state_publisher latches, and a name already taken is one
line and a non-zero exit."""

from __future__ import annotations

import itertools
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from tests.spinning import wait_until

MY_BOT = """<?xml version="1.0"?>
<robot name="my_bot">
  <link name="base_link">
    <collision><geometry><box size="0.3 0.2 0.1"/></geometry></collision>
  </link>
  <link name="left_wheel"/><link name="right_wheel"/><link name="laser_frame"/>
  <joint name="left_wheel_joint" type="continuous">
    <parent link="base_link"/><child link="left_wheel"/><origin xyz="0 0.15 0"/>
  </joint>
  <joint name="right_wheel_joint" type="continuous">
    <parent link="base_link"/><child link="right_wheel"/><origin xyz="0 -0.15 0"/>
  </joint>
  <joint name="laser_joint" type="fixed">
    <parent link="base_link"/><child link="laser_frame"/><origin xyz="0.1 0 0.2"/>
  </joint>
  <gazebo>
    <plugin name="diff_drive" filename="libgazebo_ros_diff_drive.so">
      <ros><remapping>cmd_vel:=CMD</remapping><remapping>odom:=ODOM</remapping></ros>
      <left_joint>left_wheel_joint</left_joint><right_joint>right_wheel_joint</right_joint>
      <wheel_separation>0.3</wheel_separation><wheel_diameter>0.1</wheel_diameter>
      <odometry_frame>odom</odometry_frame><robot_base_frame>base_link</robot_base_frame>
      <update_rate>20</update_rate>
    </plugin>
  </gazebo>
  <gazebo reference="laser_frame">
    <sensor name="laser" type="ray">
      <update_rate>8</update_rate>
      <ray>
        <scan><horizontal><samples>90</samples><min_angle>-1.57</min_angle>
          <max_angle>1.57</max_angle></horizontal></scan>
        <range><min>0.2</min><max>8</max></range>
      </ray>
      <plugin name="laser_controller" filename="libgazebo_ros_ray_sensor.so">
        <ros><remapping>~/out:=SCAN</remapping></ros>
        <output_type>sensor_msgs/LaserScan</output_type><frame_name>laser_frame</frame_name>
      </plugin>
    </sensor>
  </gazebo>
</robot>
"""


def _bot(prefix: str) -> str:
    return (
        MY_BOT.replace('CMD', f'{prefix}/cmd')
        .replace('ODOM', f'{prefix}/odom')
        .replace('SCAN', f'{prefix}/scan')
    )


def _run(*args: str, timeout: float = 40) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, '-m', 'ros2lite', 'run', *args],
        capture_output=True,
        text=True,
        timeout=timeout,
    )


@pytest.fixture(scope='module')
def empty_world(ros_router: str) -> Iterator[subprocess.Popen[str]]:
    """Gazebo's server alone: the 2D world with no robot, at 4x real time (one for all tests:
    their robots have names and topics of their own); the world's process."""
    from tests.conftest import Processes

    procs = Processes()
    try:
        yield procs.cli(
            'run', 'turtlebot3_gazebo', 'gazebo_2d', '--ros-args', '-p', 'robot_model:=none',
            '-p', 'world:=empty_world', '-p', 'real_time_factor:=4.0',
        )  # fmt: skip
    finally:
        procs.close()


@pytest.mark.timeout(90)
def test_a_spawned_robot_drives_from_its_plugins_topic(
    empty_world: Any, ros_context: Any, tmp_path: Path
) -> None:
    from ros2lite.executors import SingleThreadedExecutor
    from ros2lite.msgs.geometry_msgs.msg import Twist
    from ros2lite.msgs.nav_msgs.msg import Odometry
    from ros2lite.msgs.sensor_msgs.msg import LaserScan
    from ros2lite.node import Node
    from ros2lite.qos import qos_profile_sensor_data

    urdf = tmp_path / 'my_bot.urdf'
    urdf.write_text(_bot('my_bot'))
    done = _run(
        'gazebo_ros', 'spawn_entity.py', '-entity', 'my_bot', '-file', str(urdf), '-x', '1.5',
        '-y', '-0.5', '-Y', '0.0',
    )  # fmt: skip
    assert done.returncode == 0, done.stdout + done.stderr
    assert "Spawned 'my_bot'" in done.stdout + done.stderr

    node = Node('driver', context=ros_context)
    executor = SingleThreadedExecutor(context=ros_context)
    executor.add_node(node)
    odoms: list[Odometry] = []
    scans: list[LaserScan] = []
    node.create_subscription(Odometry, '/my_bot/odom', odoms.append, 10)
    node.create_subscription(LaserScan, '/my_bot/scan', scans.append, qos_profile_sensor_data)
    pub = node.create_publisher(Twist, '/my_bot/cmd', 10)

    def spin_until(predicate: Any, timeout: float = 30) -> Any:
        return wait_until(predicate, timeout, step=lambda: executor.spin_once(timeout_sec=0.02))

    try:
        spin_until(lambda: len(scans) >= 6 and odoms and pub.get_subscription_count() > 0)
        first = odoms[-1]
        assert (first.header.frame_id, first.child_frame_id) == ('odom', 'base_link')
        scan = scans[-1]
        assert (scan.header.frame_id, len(scan.ranges)) == ('laser_frame', 90)
        assert scan.range_max == pytest.approx(8.0)
        # the plugin's 8 Hz, in sim time: consecutive stamps 0.125 s apart
        stamps = [s.header.stamp.sec + s.header.stamp.nanosec * 1e-9 for s in scans[-5:]]
        gaps = [b - a for a, b in itertools.pairwise(stamps)]
        assert all(g == pytest.approx(0.125, abs=0.011) for g in gaps), gaps
        move = Twist()
        move.linear.x = 0.3
        x0 = first.pose.pose.position.x

        def moved() -> bool:
            pub.publish(move)
            return odoms[-1].pose.pose.position.x > x0 + 0.3

        spin_until(moved)
    finally:
        node.destroy_node()
        executor.shutdown()


@pytest.mark.timeout(90)
def test_create_reads_the_description_topic_and_names_are_unique(
    empty_world: Any, processes: Any, tmp_path: Path
) -> None:
    import yaml

    params = tmp_path / 'rsp.yaml'
    description = {'robot_description': _bot('twin')}
    params.write_text(yaml.safe_dump({'robot_state_publisher': {'ros__parameters': description}}))
    rsp = processes.cli(
        'run', 'robot_state_publisher', 'robot_state_publisher', '--ros-args', '--params-file',
        str(params),
    )  # fmt: skip
    done = _run('ros_gz_sim', 'create', '-name', 'twin', '-topic', 'robot_description')
    assert done.returncode == 0, done.stdout + done.stderr
    again = _run('ros_gz_sim', 'create', '-string', _bot('twin'), '-name', 'twin')
    assert again.returncode == 1
    said = [line for line in again.stderr.splitlines() if 'failed:' in line]
    assert said == ["spawning 'twin' failed: an entity named 'twin' is already in the world"]
    assert 'Traceback' not in again.stderr
    processes.stop(rsp)
    out = subprocess.run(
        [sys.executable, '-m', 'ros2lite', 'topic', 'list'], capture_output=True, text=True
    )
    assert '/twin/scan' in out.stdout and '/twin/cmd' in out.stdout, out.stdout


def test_an_executable_with_py_runs_its_module() -> None:
    from ros2lite.pkg.bundled import BUNDLED

    assert BUNDLED['gazebo_ros'] == {
        'spawn_entity.py': 'ros2lite.bundled.gazebo_ros.spawn_entity:main'
    }
    assert BUNDLED['ros_gz_sim'] == {'create': 'ros2lite.bundled.ros_gz_sim.create:main'}


@pytest.mark.timeout(90)
def test_hostile_spawn_requests_are_refused_and_the_world_runs_on(
    empty_world: subprocess.Popen[str], ros_context: Any
) -> None:
    """Any peer can publish on the spawn topic: a bad namespace, a URDF whose remapping names
    an invalid topic, a pose that is not finite are each one refusal, the half-built robot
    leaves no topic behind, and the world (its process, its physics) carries on."""
    import json
    import math

    from ros2lite.executors import SingleThreadedExecutor
    from ros2lite.msgs.rosgraph_msgs.msg import Clock
    from ros2lite.msgs.std_msgs.msg import String
    from ros2lite.node import Node
    from ros2lite.qos import DurabilityPolicy, QoSProfile
    from ros2lite.sim.spawn import SPAWN_TOPIC, SPAWNED_TOPIC

    node = Node('hostile', context=ros_context)
    executor = SingleThreadedExecutor(context=ros_context)
    executor.add_node(node)
    ids = ('ns', 'half', 'nan', 'good')
    answers: dict[str, dict[str, Any]] = {}
    clocks: list[float] = []
    latched = QoSProfile(depth=10, durability=DurabilityPolicy.TRANSIENT_LOCAL)

    def on_answer(msg: String) -> None:
        answer = json.loads(msg.data)
        if answer['id'] in ids:  # not the earlier tests' latched answers
            answers[answer['id']] = answer

    node.create_subscription(String, SPAWNED_TOPIC, on_answer, latched)
    node.create_subscription(
        Clock, '/clock', lambda m: clocks.append(m.clock.sec + m.clock.nanosec * 1e-9), 10
    )
    pub = node.create_publisher(String, SPAWN_TOPIC, 10)

    def spin_until(predicate: Any, timeout: float = 30) -> Any:
        return wait_until(predicate, timeout, step=lambda: executor.spin_once(timeout_sec=0.02))

    # the laser's topic is fine and made first; the odometry's is not
    half = _bot('half').replace('half/odom', 'half odom')
    nan_pose = json.dumps({'name': 'nan_bot', 'urdf': _bot('nb'), 'x': math.nan, 'id': 'nan'})
    assert '"x": NaN' in nan_pose  # what json.loads takes
    requests = [
        json.dumps({'name': 'ns_bot', 'urdf': _bot('ns'), 'namespace': 'bad ns', 'id': 'ns'}),
        json.dumps({'name': 'half', 'urdf': half, 'id': 'half'}),
        nan_pose,
        json.dumps({'name': 'good', 'urdf': _bot('good'), 'id': 'good'}),
    ]
    try:
        spin_until(lambda: pub.get_subscription_count() > 0)
        for text in requests:
            pub.publish(String(data=text))
        spin_until(lambda: len(answers) == len(ids))
        assert {k: a['ok'] for k, a in answers.items()} == {
            'ns': False,
            'half': False,
            'nan': False,
            'good': True,
        }
        assert "namespace '/bad ns' is invalid" in answers['ns']['message']
        assert "topic name 'half odom' is invalid" in answers['half']['message']
        assert answers['nan']['message'] == 'x must be a finite number, not nan'
        # physics still steps after every request: sim time moves on
        seen = len(clocks)
        spin_until(lambda: len(clocks) > seen + 20)
        assert clocks[-1] > clocks[seen]
        assert empty_world.poll() is None
    finally:
        node.destroy_node()
        executor.shutdown()
    out = subprocess.run(
        [sys.executable, '-m', 'ros2lite', 'topic', 'list'], capture_output=True, text=True
    )
    assert '/good/scan' in out.stdout, out.stdout
    assert '/half/scan' not in out.stdout, out.stdout
