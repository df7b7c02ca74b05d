"""A small URDF robot with a bit of everything, shared by the urdf/ tests and the packages'."""

from __future__ import annotations

__all__ = ['ARM']

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
