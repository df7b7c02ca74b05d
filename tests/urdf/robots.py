"""Robots shared by the urdf/ tests and the packages': a small URDF with a bit of everything,
and a xacro robot in a source workspace."""

from __future__ import annotations

from pathlib import Path

__all__ = ['ARM', 'DISPLAY_LAUNCH', 'bot_workspace', 'with_display_launch']

ARM = """<?xml version="1.0"?>
<robot name="arm">
  <material name="blue"><color rgba="0 0 0.8 1"/></material>
  <link name="base_link">
    <visual>
      <origin xyz="0 0 0.05" rpy="0 0 0"/>
      <geometry><box size="0.4 0.3 0.1"/></geometry>
      <material name="blue"/>
    </visual>
    <collision><geometry><box size="0.4 0.3 0.1"/></geometry></collision>
  </link>
  <link name="shoulder">
    <visual>
      <geometry><cylinder radius="0.05" length="0.3"/></geometry>
      <material name="white"><color rgba="1 1 1 1"/></material>
    </visual>
  </link>
  <link name="forearm">
    <visual>
      <geometry>
        <mesh filename="package://arm_description/meshes/forearm.stl" scale="0.001 0.001 0.001"/>
      </geometry>
      <material name="white"/>
    </visual>
  </link>
  <link name="slider"><visual><geometry><sphere radius="0.02"/></geometry></visual></link>
  <link name="finger_left"/>
  <link name="finger_right"/>
  <link name="camera"/>
  <link name="wheel"/>
  <joint name="base_to_shoulder" type="fixed">
    <parent link="base_link"/><child link="shoulder"/>
    <origin xyz="0 0 0.1" rpy="0 0 1.5707963267948966"/>
  </joint>
  <joint name="elbow" type="revolute">
    <parent link="shoulder"/><child link="forearm"/>
    <origin xyz="0 0 0.3"/>
    <axis xyz="0 1 0"/>
    <limit lower="-1.5" upper="1.5" effort="10" velocity="1"/>
  </joint>
  <joint name="slide" type="prismatic">
    <parent link="forearm"/><child link="slider"/>
    <origin xyz="0.2 0 0"/>
    <axis xyz="2 0 0"/>
    <limit lower="0" upper="0.1" effort="5" velocity="0.5"/>
  </joint>
  <joint name="finger_left_joint" type="prismatic">
    <parent link="slider"/><child link="finger_left"/>
    <axis xyz="0 1 0"/>
    <limit lower="0" upper="0.04" effort="1" velocity="0.1"/>
  </joint>
  <joint name="finger_right_joint" type="prismatic">
    <parent link="slider"/><child link="finger_right"/>
    <axis xyz="0 1 0"/>
    <limit lower="-0.04" upper="0" effort="1" velocity="0.1"/>
    <mimic joint="finger_left_joint" multiplier="-1" offset="0"/>
  </joint>
  <joint name="camera_mount" type="floating">
    <parent link="base_link"/><child link="camera"/>
    <origin xyz="0.1 0 0.2" rpy="0 0.5 0"/>
  </joint>
  <joint name="wheel_joint" type="continuous">
    <parent link="base_link"/><child link="wheel"/>
    <origin xyz="0 0.2 0" rpy="-1.5707963267948966 0 0"/>
    <axis xyz="0 0 1"/>
  </joint>
  <gazebo reference="wheel"><mu1>0.5</mu1></gazebo>
</robot>
"""


_MANIFEST = """<?xml version="1.0"?>
<package format="3">
  <name>bot_description</name><version>0.0.1</version><description>a test robot</description>
  <maintainer email="test@invalid">test</maintainer><license>MIT</license>
  <export><build_type>ament_python</build_type></export>
</package>
"""
_BOT = """<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro" name="bot">
  <xacro:arg name="width" default="0.2"/>
  <xacro:property name="w" value="$(arg width)"/>
  <xacro:include filename="$(find bot_description)/urdf/parts.xacro"/>
  <material name="orange"><color rgba="1 0.5 0 1"/></material>
  <link name="base_link">
    <visual><geometry><box size="${w} ${w} 0.1"/></geometry><material name="orange"/></visual>
  </link>
  <xacro:wheel side="left" y="${w/2}"/>
  <xacro:wheel side="right" y="${-w/2}"/>
</robot>
"""
_PARTS = """<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="wheel" params="side y">
    <link name="${side}_wheel">
      <visual><geometry><cylinder radius="0.05" length="0.02"/></geometry></visual>
    </link>
    <joint name="${side}_wheel_joint" type="continuous">
      <parent link="base_link"/><child link="${side}_wheel"/>
      <origin xyz="0 ${y} 0"/><axis xyz="0 1 0"/>
    </joint>
  </xacro:macro>
</robot>
"""


def bot_workspace(root: Path) -> Path:
    """A source workspace under `root` holding `bot_description`: a xacro robot (an argument,
    a property, an include found by `$(find bot_description)`, a macro used twice)."""
    ws = root / 'ws'
    pkg = ws / 'src' / 'bot_description'
    (pkg / 'urdf').mkdir(parents=True)
    (pkg / 'package.xml').write_text(_MANIFEST)
    (pkg / 'urdf' / 'bot.urdf.xacro').write_text(_BOT)
    (pkg / 'urdf' / 'parts.xacro').write_text(_PARTS)
    return ws


# Jazzy's URDF tutorial's display.launch.py, in its shape: urdf_launch's display.launch.py
# included with this package's xacro file (xacro -> robot_description -> robot_state_publisher,
# joint_state_publisher or its GUI by `gui`, and rviz2, optional here: another branch's)
DISPLAY_LAUNCH = """
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument, IncludeLaunchDescription
from launch.substitutions import LaunchConfiguration, PathJoinSubstitution
from launch_ros.substitutions import FindPackageShare


def generate_launch_description():
    return LaunchDescription([
        DeclareLaunchArgument('gui', default_value='true', choices=['true', 'false']),
        DeclareLaunchArgument('rviz', default_value='true', choices=['true', 'false']),
        DeclareLaunchArgument('model', default_value='urdf/bot.urdf.xacro'),
        IncludeLaunchDescription(
            PathJoinSubstitution([FindPackageShare('urdf_launch'), 'launch', 'display.launch.py']),
            launch_arguments={
                'urdf_package': 'bot_description',
                'urdf_package_path': LaunchConfiguration('model'),
                'jsp_gui': LaunchConfiguration('gui'),
                'rviz': LaunchConfiguration('rviz'),
            }.items(),
        ),
    ])
"""


def with_display_launch(ws: Path) -> Path:
    """`ws` with the tutorial-shaped launch file in bot_description/launch/."""
    launch = ws / 'src' / 'bot_description' / 'launch'
    launch.mkdir(exist_ok=True)
    (launch / 'display.launch.py').write_text(DISPLAY_LAUNCH)
    return ws
