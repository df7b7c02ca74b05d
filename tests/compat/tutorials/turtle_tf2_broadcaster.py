"""A broadcaster as the ROS 2 tf2 tutorial "Writing a broadcaster (Python)" teaches it: each
pose of a turtle becomes the transform from `world` to the turtle's frame on /tf."""

import math

import numpy as np
import rclpy
from geometry_msgs.msg import TransformStamped
from rclpy.node import Node
from tf2_ros import TransformBroadcaster
from turtlesim.msg import Pose


def quaternion_from_euler(ai, aj, ak):
    ai /= 2.0
    aj /= 2.0
    ak /= 2.0
    ci = math.cos(ai)
    si = math.sin(ai)
    cj = math.cos(aj)
    sj = math.sin(aj)
    ck = math.cos(ak)
    sk = math.sin(ak)
    cc = ci * ck
    cs = ci * sk
    sc = si * ck
    ss = si * sk

    q = np.empty((4,))
    q[0] = cj * sc - sj * cs
    q[1] = cj * ss + sj * cc
    q[2] = cj * cs - sj * sc
    q[3] = cj * cc + sj * ss

    return q


class FramePublisher(Node):
    def __init__(self):
        super().__init__('turtle_tf2_frame_publisher')

        # which turtle this node follows, from the `turtlename` parameter
        self.turtlename = (
            self.declare_parameter('turtlename', 'turtle').get_parameter_value().string_value
        )

        self.tf_broadcaster = TransformBroadcaster(self)

        # every pose of the turtle is turned into a transform
        self.subscription = self.create_subscription(
            Pose, f'/{self.turtlename}/pose', self.handle_turtle_pose, 1
        )
        self.subscription  # prevent unused variable warning

    def handle_turtle_pose(self, msg):
        t = TransformStamped()

        t.header.stamp = self.get_clock().now().to_msg()
        t.header.frame_id = 'world'
        t.child_frame_id = self.turtlename

        # a turtle lives in the plane: x and y from the pose, z stays 0
        t.transform.translation.x = msg.x
        t.transform.translation.y = msg.y
        t.transform.translation.z = 0.0

        # and it only turns about z
        q = quaternion_from_euler(0, 0, msg.theta)
        t.transform.rotation.x = q[0]
        t.transform.rotation.y = q[1]
        t.transform.rotation.z = q[2]
        t.transform.rotation.w = q[3]

        self.tf_broadcaster.sendTransform(t)


def main():
    rclpy.init()
    node = FramePublisher()
    try:
        rclpy.spin(node)
    except KeyboardInterrupt:
        pass

    rclpy.shutdown()


if __name__ == '__main__':
    main()
