"""The robot the RobotModel pixel test looks at, and its joint states from a process the test
controls: run as a program, it publishes /joint_states with the arm's joint at ANGLE (radians)
at 10 Hz, as joint_state_publisher would, until stopped."""

from __future__ import annotations

import contextlib
import sys

BASE_COLOUR = (0, 200, 0)  # a green base on base_link
ARM_COLOUR = (255, 220, 0)  # a yellow arm on a revolute joint round base_link's z


def rgba(colour: tuple[int, int, int]) -> str:
    return ' '.join(f'{c / 255:.4f}' for c in colour) + ' 1'


URDF = f"""<robot name="armed">
  <material name="green"><color rgba="{rgba(BASE_COLOUR)}"/></material>
  <material name="yellow"><color rgba="{rgba(ARM_COLOUR)}"/></material>
  <link name="base_link">
    <visual><geometry><box size="0.8 0.8 0.3"/></geometry><material name="green"/></visual>
  </link>
  <link name="arm">
    <visual>
      <origin xyz="0.7 0 0"/>
      <geometry><box size="1.1 0.25 0.25"/></geometry><material name="yellow"/>
    </visual>
  </link>
  <joint name="swing" type="revolute">
    <parent link="base_link"/><child link="arm"/><origin xyz="0 0 0.3"/><axis xyz="0 0 1"/>
    <limit lower="-3.2" upper="3.2" effort="1" velocity="1"/>
  </joint>
</robot>
"""


def main() -> None:
    import ros2lite
    from ros2lite.executors import ExternalShutdownException
    from ros2lite.msgs.sensor_msgs.msg import JointState

    angle = float(sys.argv[1])
    ros2lite.init()
    node = ros2lite.create_node('test_joint_states')
    pub = node.create_publisher(JointState, '/joint_states', 10)

    def tick() -> None:
        msg = JointState()
        msg.header.stamp = node.get_clock().now().to_msg()
        msg.name, msg.position = ['swing'], [angle]
        pub.publish(msg)

    node.create_timer(0.1, tick)
    with contextlib.suppress(KeyboardInterrupt, ExternalShutdownException):
        ros2lite.spin(node)


if __name__ == '__main__':
    main()
