"""turtlebot3_gazebo on real routers: the launch line starts the 2D TurtleBot3, a course's
obstacle-avoidance node (plain rclpy, through `ros2lite env`) drives it 60 s of sim time at a
real-time factor of 10 without touching anything, `/odom` follows `/cmd_vel`, and
`/reset_simulation` brings the robot back (each test with a simulator of its own; the launch
that tests only watch is in test_empty_world, so that it never runs beside these)."""

from __future__ import annotations

import math
import re
import shlex
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

import pytest

from tests.bundled.turtlebot3_gazebo.launching import launch
from tests.spinning import wait_until

HERE = Path(__file__).parent


def _echo(topic: str, *extra: str, timeout: float = 20) -> str:
    out = subprocess.run(
        [sys.executable, '-m', 'ros2lite', 'topic', 'echo', '--once', *extra, topic],
        capture_output=True,
        text=True,
        timeout=timeout,
    )
    assert out.returncode == 0, out.stderr
    return out.stdout


def _field(text: str, name: str) -> float:
    match = re.search(rf'^\s*{name}: (\S+)$', text, re.M)
    assert match, text
    return float(match.group(1))


@pytest.mark.timeout(90)
def test_obstacle_avoidance_drives_a_minute_without_collision(processes: Any) -> None:
    sim = launch(processes, 'turtlebot3_world.launch.py', 'real_time_factor:=10.0')
    line = (
        f'eval "$({shlex.quote(sys.executable)} -m ros2lite env)" && '
        f'exec {shlex.quote(sys.executable)} {HERE / "obstacle_avoider.py"} 60'
    )
    started = time.monotonic()
    driver = processes.start(['bash', '-c', line])
    out, err = driver.communicate(timeout=60)
    wall = time.monotonic() - started
    assert driver.returncode == 0, err
    match = re.search(r'done: (\S+) s, travelled (\S+) m', out)
    assert match, out + err
    assert float(match.group(2)) > 2.0, out  # it really drove
    assert wall < 40, wall  # 60 s of sim time at 10x, with start-up
    log = ''.join(sim.lines)  # type: ignore[attr-defined]
    assert 'hit an obstacle' not in log, log + out


@pytest.mark.timeout(60)
def test_reset_simulation_puts_the_robot_back(processes: Any, ros_context: Any) -> None:
    from ros2lite.executors import SingleThreadedExecutor
    from ros2lite.msgs.geometry_msgs.msg import Twist
    from ros2lite.msgs.nav_msgs.msg import Odometry
    from ros2lite.msgs.rosgraph_msgs.msg import Clock
    from ros2lite.msgs.std_srvs.srv import Empty
    from ros2lite.node import Node

    sim = processes.cli(
        'run',
        'turtlebot3_gazebo',
        'gazebo_2d',
        '--ros-args',
        '-p',
        'world:=empty_world',
        '-p',
        'real_time_factor:=5.0',
    )
    node = Node('resetter', context=ros_context)
    executor = SingleThreadedExecutor(context=ros_context)
    executor.add_node(node)
    pub = node.create_publisher(Twist, '/cmd_vel', 10)
    odoms: list[Odometry] = []
    clocks: list[float] = []
    node.create_subscription(Odometry, '/odom', odoms.append, 10)
    node.create_subscription(
        Clock, '/clock', lambda m: clocks.append(m.clock.sec + m.clock.nanosec * 1e-9), 10
    )
    client = node.create_client(Empty, '/reset_simulation')

    def spin_until(predicate: Any, timeout: float = 20) -> Any:
        return wait_until(predicate, timeout, step=lambda: executor.spin_once(timeout_sec=0.02))

    def stamp(msg: Odometry) -> float:
        return msg.header.stamp.sec + msg.header.stamp.nanosec * 1e-9

    try:
        move = Twist()
        move.linear.x = 0.2
        spin_until(lambda: odoms and pub.get_subscription_count() > 0)
        pub.publish(move)
        spin_until(lambda: odoms[-1].pose.pose.position.x > 0.3)
        pub.publish(Twist())
        assert client.wait_for_service(timeout_sec=10)
        before = stamp(odoms[-1])
        future = client.call_async(Empty.Request())
        spin_until(future.done)
        # sim time starts again from zero, and the odometry with it
        spin_until(lambda: clocks[-1] < before and stamp(odoms[-1]) < before)
        position = odoms[-1].pose.pose.position
        assert math.hypot(position.x, position.y) < 1e-6, position
    finally:
        executor.shutdown()
        node.destroy_node()
        processes.stop(sim)


@pytest.mark.timeout(60)
def test_odometry_integrates_the_commanded_arc(processes: Any, ros_context: Any) -> None:
    """0.2 m/s and 0.4 rad/s for 5 s of sim time: a 0.5 m-radius arc through 2 rad."""
    from ros2lite.executors import SingleThreadedExecutor
    from ros2lite.msgs.geometry_msgs.msg import Twist
    from ros2lite.msgs.nav_msgs.msg import Odometry
    from ros2lite.node import Node
    from ros2lite.tf2.math import rpy_from_quaternion

    sim = processes.cli(
        'run',
        'turtlebot3_gazebo',
        'gazebo_2d',
        '--ros-args',
        '-p',
        'world:=empty_world',
        '-p',
        'x_pose:=0.0',
        '-p',
        'y_pose:=0.0',
        '-p',
        'real_time_factor:=2.0',
        '-p',
        'odom_noise:=0.01',
        '-p',
        'seed:=7',
    )
    node = Node('arc_driver', context=ros_context)
    executor = SingleThreadedExecutor(context=ros_context)
    executor.add_node(node)
    pub = node.create_publisher(Twist, '/cmd_vel', 10)
    last: list[Odometry] = []
    node.create_subscription(Odometry, '/odom', last.append, 10)

    def stamp() -> float:
        s = last[-1].header.stamp
        return s.sec + s.nanosec * 1e-9

    def spin_until(predicate: Any, timeout: float) -> None:
        wait_until(predicate, timeout, step=lambda: executor.spin_once(timeout_sec=0.02))

    try:
        spin_until(lambda: last, 20)
        # odometry flowing does not mean the simulator hears us yet: one command, once heard
        spin_until(lambda: pub.get_subscription_count() > 0, 20)
        # the simulator's robot alone (another beside it once gave this test yaw 0.0)
        assert node.count_publishers('/odom') == 1
        move = Twist()
        move.linear.x, move.angular.z = 0.2, 0.4
        t0 = stamp()
        pub.publish(move)
        spin_until(lambda: stamp() >= t0 + 5.0, 20)
        pub.publish(Twist())
        spin_until(lambda: abs(last[-1].twist.twist.linear.x) < 1e-9 and stamp() > t0 + 6, 20)
    finally:
        executor.shutdown()
        node.destroy_node()
        processes.stop(sim)
    pose = last[-1].pose.pose
    yaw = rpy_from_quaternion(
        (pose.orientation.x, pose.orientation.y, pose.orientation.z, pose.orientation.w)
    )[2]
    # the pose lies on the commanded 0.5 m-radius arc (the wheels' 1 m/s² ramps bend it by
    # millimetres, the 1 % wheel noise by less)
    assert abs(pose.position.x - 0.5 * math.sin(yaw)) < 0.03, (pose.position, yaw)
    assert abs(pose.position.y - 0.5 * (1 - math.cos(yaw))) < 0.03, (pose.position, yaw)
    # and it turned 0.4 rad/s for as long as odometry says it drove (at half speed at either
    # end, where the ramps are alike): when the commands arrived is the machine's business,
    # a loaded one delays them by tenths of a second of sim time
    moving = [m for m in last if m.twist.twist.linear.x > 0.1]
    first, end = (
        m.header.stamp.sec + m.header.stamp.nanosec * 1e-9 for m in (moving[0], moving[-1])
    )
    assert end - first > 3.0, (first, end)
    assert abs(yaw - 0.4 * (end - first)) < 0.1, (yaw, end - first)


@pytest.mark.timeout(60)
def test_a_whole_number_sets_a_decimal_setting_and_a_word_is_one_line(ros_router: str) -> None:
    """`real_time_factor:=10` is a factor of 10 (a course types it so); a word is refused in
    one line and the process ends (it used to hang after a traceback at shutdown)."""
    line = [sys.executable, '-m', 'ros2lite', 'run', 'turtlebot3_gazebo', 'gazebo_2d']
    line += ['--ros-args', '-p', 'world:=empty_world']
    bad = subprocess.run(
        [*line, '-p', 'real_time_factor:=fast'], capture_output=True, text=True, timeout=30
    )
    assert bad.returncode == 1, bad.stderr
    assert "parameter 'real_time_factor' must be a float, not 'fast'" in bad.stderr
    assert 'Traceback' not in bad.stderr + bad.stdout
    sim = subprocess.Popen(
        [*line, '-p', 'real_time_factor:=10', '-p', 'x_pose:=1'],
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        text=True,
    )
    seen: list[str] = []
    try:
        assert sim.stdout is not None
        for text in sim.stdout:
            seen.append(text)
            if 'real-time factor' in text:
                break
        assert "world 'empty_world', real-time factor 10\n" in seen[-1], seen
        assert any('burger at (1.00, ' in s for s in seen), seen
    finally:
        sim.send_signal(2)
        sim.wait(20)
