"""A workspace robot's URDF Gazebo tags read into the simulator's spec; our own robots'
descriptions parse with ros2lite.urdf."""

from __future__ import annotations

import json
import math
import re

import pytest

from ros2lite.sim.errors import SimError
from ros2lite.sim.robots import ROBOTS, urdf
from ros2lite.sim.spawn import SpawnRequest, spec_from_urdf
from ros2lite.urdf import parse_urdf

MY_BOT = """<?xml version="1.0"?>
<robot name="my_bot">
  <link name="base_link">
    <collision><geometry><box size="0.4 0.3 0.1"/></geometry></collision>
  </link>
  <link name="left_wheel"/><link name="right_wheel"/><link name="laser_frame"/>
  <joint name="left_wheel_joint" type="continuous">
    <parent link="base_link"/><child link="left_wheel"/><origin xyz="0 0.175 0"/>
  </joint>
  <joint name="right_wheel_joint" type="continuous">
    <parent link="base_link"/><child link="right_wheel"/><origin xyz="0 -0.175 0"/>
  </joint>
  <joint name="laser_joint" type="fixed">
    <parent link="base_link"/><child link="laser_frame"/><origin xyz="0.1 0 0.175"/>
  </joint>
  <gazebo>
    <plugin name="diff_drive" filename="libgazebo_ros_diff_drive.so">
      <left_joint>left_wheel_joint</left_joint><right_joint>right_wheel_joint</right_joint>
      <wheel_separation>0.35</wheel_separation><wheel_diameter>0.1</wheel_diameter>
      <max_wheel_acceleration>10.0</max_wheel_acceleration>
      <publish_odom_tf>true</publish_odom_tf><odometry_frame>odom</odometry_frame>
      <robot_base_frame>base_link</robot_base_frame><update_rate>30</update_rate>
    </plugin>
  </gazebo>
  <gazebo reference="laser_frame">
    <sensor name="laser" type="ray">
      <update_rate>10</update_rate>
      <ray>
        <scan><horizontal><samples>360</samples><min_angle>-3.14</min_angle>
          <max_angle>3.14</max_angle></horizontal></scan>
        <range><min>0.3</min><max>12</max></range>
      </ray>
      <plugin name="laser_controller" filename="libgazebo_ros_ray_sensor.so">
        <ros><remapping>~/out:=scan</remapping></ros>
        <output_type>sensor_msgs/LaserScan</output_type><frame_name>laser_frame</frame_name>
      </plugin>
    </sensor>
  </gazebo>
</robot>
"""


def test_the_plugins_tags_make_the_spec() -> None:
    spec = spec_from_urdf(MY_BOT)
    assert spec.name == 'my_bot'
    assert spec.limits.wheel_separation == 0.35 and spec.limits.wheel_radius == 0.05
    assert spec.limits.footprint_radius == pytest.approx(0.25)
    assert (spec.cmd_vel, spec.odom_topic, spec.base_frame) == ('cmd_vel', 'odom', 'base_link')
    assert spec.odom_rate == 30
    laser = spec.laser
    assert (laser.topic, laser.frame_id, laser.samples, laser.rate) == (
        'scan',
        'laser_frame',
        360,
        10,
    )
    assert (laser.range_min, laser.range_max, laser.x) == (0.3, 12.0, pytest.approx(0.1))
    assert spec.wheel_joints == ('left_wheel_joint', 'right_wheel_joint')


def test_a_robot_without_a_drive_is_one_line() -> None:
    with pytest.raises(SimError, match='no diff-drive plugin'):
        spec_from_urdf('<robot name="r"><link name="a"/></robot>')


@pytest.mark.parametrize('name', sorted(ROBOTS))
def test_our_descriptions_parse(name: str) -> None:
    spec = ROBOTS[name]
    robot = parse_urdf(urdf(spec))
    assert robot.root == spec.base_frame
    assert spec.laser.frame_id in robot.links
    for joint in spec.wheel_joints:
        assert robot.joints[joint].type == 'continuous'
    assert not math.isnan(spec.limits.wheel_separation)


@pytest.mark.parametrize(
    ('fields', 'said'),
    [
        ({'x': math.nan}, 'x must be a finite number, not nan'),
        ({'yaw': math.inf}, 'yaw must be a finite number, not inf'),
        ({'namespace': 'bad ns'}, "namespace '/bad ns' is invalid"),
        ({'namespace': 'a//b'}, "namespace '/a//b' is invalid"),
    ],
)
def test_a_request_from_a_peer_is_validated(fields: dict[str, object], said: str) -> None:
    request = SpawnRequest.from_json(json.dumps({'name': 'r', 'urdf': MY_BOT, **fields}))
    with pytest.raises(SimError, match=re.escape(said)):
        request.validate()
    SpawnRequest.from_json(
        json.dumps({'name': 'r', 'urdf': MY_BOT, 'namespace': '/a/b'})
    ).validate()
