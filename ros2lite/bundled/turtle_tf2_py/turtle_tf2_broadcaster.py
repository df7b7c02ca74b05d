"""`turtle_tf2_broadcaster`: every pose of the turtle named by the `turtlename` parameter
becomes the transform `world` -> turtle on /tf (the tf2 tutorial's broadcaster)."""

from __future__ import annotations

import sys

from ros2lite.bundled.runner import run_node
from ros2lite.msgs.geometry_msgs.msg import TransformStamped
from ros2lite.msgs.turtlesim.msg import Pose
from ros2lite.node import Node
from ros2lite.tf2 import TransformBroadcaster
from ros2lite.tf2.math import quaternion_from_rpy


class FramePublisher(Node):
    """Turns a turtle's poses into its frame in `world`."""

    def __init__(self) -> None:
        super().__init__('turtle_tf2_frame_publisher')
        self.turtlename = str(self.declare_parameter('turtlename', 'turtle').value)
        self.tf_broadcaster = TransformBroadcaster(self)
        self.subscription = self.create_subscription(
            Pose, f'/{self.turtlename}/pose', self.handle_turtle_pose, 1
        )

    def handle_turtle_pose(self, msg: Pose) -> None:
        """The turtle lives in the plane: x, y, and a turn about z."""
        t = TransformStamped()
        t.header.stamp = self.get_clock().now().to_msg()
        t.header.frame_id = 'world'
        t.child_frame_id = self.turtlename
        t.transform.translation.x = msg.x
        t.transform.translation.y = msg.y
        t.transform.translation.z = 0.0
        q = t.transform.rotation
        q.x, q.y, q.z, q.w = quaternion_from_rpy(0.0, 0.0, msg.theta)
        self.tf_broadcaster.sendTransform(t)


def main(args: list[str] | None = None) -> int:
    """`turtle_tf2_broadcaster`'s entry point."""
    return run_node(FramePublisher, args)


if __name__ == '__main__':
    sys.exit(main())
