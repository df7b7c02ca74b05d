"""turtlebot3_gazebo's `empty_world.launch.py`, started once for the tests that only watch it:
`/scan` comes at the LDS's 5 Hz, and robot_state_publisher takes the description. A module of
its own, so that its robot on `/odom` and `/clock` never runs beside a test's own simulator."""

from __future__ import annotations

import os
import subprocess
import threading
from collections.abc import Iterator
from typing import Any

import pytest

from tests.bundled.turtlebot3_gazebo.launching import launch
from tests.spinning import wait_until


@pytest.fixture(scope='module')
def empty_world(ros_router: str) -> Iterator[subprocess.Popen[str]]:
    """One `empty_world.launch.py` for the tests that only watch it (started once: a launch
    with robot_state_publisher costs seconds on a loaded machine), with `gui:=false` and a
    DISPLAY that is never there: a window it opened would say so in the launch's output."""
    from tests.conftest import Processes

    procs = Processes()
    env = {**os.environ, 'DISPLAY': ':99999'}
    try:
        yield launch(procs, 'empty_world.launch.py', 'gui:=false', env=env)
    finally:
        procs.close()


@pytest.mark.timeout(60)
def test_scan_comes_at_the_lds_rate(empty_world: Any, processes: Any) -> None:
    hz = processes.cli('topic', 'hz', '/scan', '--window', '20')
    rates: list[float] = []

    def read() -> None:
        assert hz.stdout is not None
        for line in hz.stdout:
            if line.startswith('average rate:'):
                rates.append(float(line.split()[-1]))

    threading.Thread(target=read, daemon=True).start()
    # hz prints every second once 20 scans (4 s) are in its window
    wait_until(lambda: len(rates) >= 3, timeout=20)
    processes.stop(hz)
    assert abs(rates[-1] - 5.0) / 5.0 < 0.02, rates


@pytest.mark.timeout(60)
def test_robot_state_publisher_takes_the_description(empty_world: Any, ros_context: Any) -> None:
    """robot_state_publisher is installed (bundled), so the launch file hands it the URDF:
    `/robot_description` and the fixed frames are its, the wheels' frames it makes from the
    simulator's `/joint_states`."""
    from ros2lite.executors import SingleThreadedExecutor
    from ros2lite.msgs.std_msgs.msg import String
    from ros2lite.msgs.tf2_msgs.msg import TFMessage
    from ros2lite.node import Node
    from ros2lite.qos import DurabilityPolicy, QoSProfile

    node = Node('handover', context=ros_context)
    executor = SingleThreadedExecutor(context=ros_context)
    executor.add_node(node)
    latched = QoSProfile(depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL)
    descriptions: list[str] = []
    wheels: list[tuple[str, str]] = []
    statics: list[tuple[str, str]] = []
    node.create_subscription(
        String, '/robot_description', lambda m: descriptions.append(m.data), latched
    )

    def on_tf(msg: TFMessage) -> None:
        wheels.extend((t.header.frame_id, t.child_frame_id) for t in msg.transforms)

    node.create_subscription(TFMessage, '/tf', on_tf, 100)
    node.create_subscription(
        TFMessage,
        '/tf_static',
        lambda m: statics.extend((t.header.frame_id, t.child_frame_id) for t in m.transforms),
        latched,
    )

    def spin_until(predicate: Any, timeout: float = 20) -> Any:
        return wait_until(predicate, timeout, step=lambda: executor.spin_once(timeout_sec=0.02))

    try:
        both = {('base_link', 'wheel_left_link'), ('base_link', 'wheel_right_link')}
        spin_until(lambda: descriptions and both <= set(wheels) and statics)
        assert '<robot name="burger">' in descriptions[0]
        assert ('base_footprint', 'base_link') in statics, statics

        def by(topic: str) -> set[str]:
            return {i.node_name for i in node.get_publishers_info_by_topic(topic)}

        spin_until(lambda: by('/robot_description') and by('/joint_states'))
        assert by('/robot_description') == {'robot_state_publisher'}
        assert by('/tf_static') == {'robot_state_publisher'}
        assert by('/joint_states') == {'gazebo'}
        log = ''.join(empty_world.lines)
        assert 'top_window' not in log and 'robot_state_publisher' in log, log
    finally:
        executor.shutdown()
        node.destroy_node()
