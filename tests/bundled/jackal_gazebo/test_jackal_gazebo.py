"""jackal_gazebo on a real router: a course's own world file loads through
custom_world.launch.py, and the Jackal's front laser sees the crate placed in it; /odom is
the controller's odometry in odom -> base_link."""

from __future__ import annotations

import math
import subprocess
from pathlib import Path
from typing import Any

import pytest

from tests.spinning import wait_until

WORLD = """<?xml version="1.0"?>
<sdf version="1.6">
  <world name="course">
    <model name="ground_plane"><static>true</static><link name="link">
      <collision name="c"><geometry><plane><normal>0 0 1</normal><size>100 100</size></plane>
      </geometry></collision></link></model>
    <model name="crate"><pose>3 0 0.5 0 0 0</pose><static>true</static><link name="link">
      <collision name="c"><geometry><box><size>1 1 1</size></box></geometry></collision>
    </link></model>
  </world>
</sdf>
"""


@pytest.mark.timeout(60)
def test_custom_world_crate_is_seen_by_the_front_laser(
    processes: Any, ros_context: Any, tmp_path: Path
) -> None:
    from ros2lite.executors import SingleThreadedExecutor
    from ros2lite.msgs.nav_msgs.msg import Odometry
    from ros2lite.msgs.sensor_msgs.msg import LaserScan
    from ros2lite.node import Node
    from ros2lite.qos import qos_profile_sensor_data

    world = tmp_path / 'course.world'
    world.write_text(WORLD)
    sim = processes.cli(
        'launch',
        'jackal_gazebo',
        'custom_world.launch.py',
        f'world:={world}',
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
    )
    node = Node('jackal_checker', context=ros_context)
    executor = SingleThreadedExecutor(context=ros_context)
    executor.add_node(node)
    scans: list[LaserScan] = []
    odoms: list[Odometry] = []
    node.create_subscription(LaserScan, '/front/scan', scans.append, qos_profile_sensor_data)
    node.create_subscription(Odometry, '/odom', odoms.append, 10)
    try:
        wait_until(lambda: scans and odoms, 40, step=lambda: executor.spin_once(timeout_sec=0.05))
    finally:
        executor.shutdown()
        node.destroy_node()
        out, _ = processes.stop(sim)
    scan = scans[-1]
    assert scan.header.frame_id == 'front_laser'
    assert len(scan.ranges) == 720
    assert scan.angle_min == pytest.approx(-2.35619, abs=1e-5)
    ahead = round((0.0 - scan.angle_min) / scan.angle_increment)
    # the crate's near face is at x = 2.5, the laser 0.12 m ahead of base_link
    assert scan.ranges[ahead] == pytest.approx(2.38, abs=0.01)
    assert math.isinf(scan.ranges[0])  # nothing else in this world
    assert (odoms[-1].header.frame_id, odoms[-1].child_frame_id) == ('odom', 'base_link')
    assert 'Clearpath Jackal' in out
