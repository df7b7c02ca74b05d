"""tiago_gazebo as the book's br2_tiago reaches it: a workspace holding a br2_tiago whose
sim.launch.py includes tiago_gazebo's tiago_gazebo.launch.py (world_name and PAL's other
arguments), launched with `world:=small_office`; teleop on key_vel moves the base, the head
camera publishes pictures, and key_vel outranks nav_vel in the twist multiplexer."""

from __future__ import annotations

import subprocess
from pathlib import Path
from typing import Any

import pytest

from tests.spinning import wait_until

# the book's package as a reader clones it: a launch file that includes PAL's (our words)
SIM_LAUNCH = """
import os

from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument, IncludeLaunchDescription
from launch.launch_description_sources import PythonLaunchDescriptionSource
from launch.substitutions import LaunchConfiguration


def generate_launch_description():
    share = get_package_share_directory('tiago_gazebo')
    include = IncludeLaunchDescription(
        PythonLaunchDescriptionSource(os.path.join(share, 'launch', 'tiago_gazebo.launch.py')),
        launch_arguments={'world_name': LaunchConfiguration('world'), 'arm': 'no-arm',
                          'is_public_sim': 'True'}.items(),
    )
    return LaunchDescription([DeclareLaunchArgument('world', default_value='home'), include])
"""
PACKAGE_XML = """<?xml version="1.0"?>
<package format="3">
  <name>br2_tiago</name><version>0.0.0</version><description>TIAGo sim</description>
  <maintainer email="reader@invalid">reader</maintainer><license>Apache-2.0</license>
  <buildtool_depend>ament_cmake</buildtool_depend>
  <export><build_type>ament_cmake</build_type></export>
</package>
"""


@pytest.mark.timeout(60)
def test_br2_tiago_sim_launch_drives_on_key_vel(
    processes: Any, ros_context: Any, tmp_path: Path
) -> None:
    from ros2lite.executors import SingleThreadedExecutor
    from ros2lite.msgs.geometry_msgs.msg import Twist
    from ros2lite.msgs.nav_msgs.msg import Odometry
    from ros2lite.msgs.sensor_msgs.msg import Image, LaserScan
    from ros2lite.node import Node
    from ros2lite.qos import qos_profile_sensor_data

    package = tmp_path / 'br2_ws' / 'src' / 'book_ros2' / 'br2_tiago'
    (package / 'launch').mkdir(parents=True)
    (package / 'launch' / 'sim.launch.py').write_text(SIM_LAUNCH)
    (package / 'package.xml').write_text(PACKAGE_XML)
    (package / 'CMakeLists.txt').write_text('cmake_minimum_required(VERSION 3.8)\n')
    sim = processes.cli(
        'launch',
        'br2_tiago',
        'sim.launch.py',
        'world:=small_office',
        cwd=tmp_path / 'br2_ws',
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
    )
    node = Node('tiago_checker', context=ros_context)
    executor = SingleThreadedExecutor(context=ros_context)
    executor.add_node(node)
    odoms: list[Odometry] = []
    images: list[Image] = []
    scans: list[LaserScan] = []
    node.create_subscription(Odometry, '/mobile_base_controller/odom', odoms.append, 10)
    node.create_subscription(
        Image, '/head_front_camera/rgb/image_raw', images.append, qos_profile_sensor_data
    )
    node.create_subscription(LaserScan, '/scan_raw', scans.append, qos_profile_sensor_data)
    key = node.create_publisher(Twist, '/key_vel', 10)
    nav = node.create_publisher(Twist, '/nav_vel', 10)
    forward, backward = Twist(), Twist()
    forward.linear.x, backward.linear.x = 0.3, -0.3

    def drive() -> None:
        key.publish(forward)
        nav.publish(backward)  # lower priority than the keyboard: ignored while it talks
        executor.spin_once(timeout_sec=0.05)

    try:
        wait_until(
            lambda: odoms and images and scans,
            40,
            step=lambda: executor.spin_once(timeout_sec=0.05),
        )
        wait_until(lambda: odoms[-1].pose.pose.position.x > 0.2, 20, step=drive)
    finally:
        executor.shutdown()
        node.destroy_node()
        out, _ = processes.stop(sim)
    image = images[-1]
    assert (image.width, image.height, image.encoding) == (320, 240, 'rgb8')
    assert len(image.data) == 320 * 240 * 3
    assert len(set(bytes(image.data))) > 3  # walls, floor and sky, not one flat colour
    assert scans[-1].header.frame_id == 'base_laser_link'
    assert odoms[-1].child_frame_id == 'base_footprint'
    assert 'PAL TIAGo' in out and "world 'small_office'" in out
