"""`mimic`: makes one turtle copy another's motion (turtlesim's tutorial node).

Node `/turtle_mimic` turns each pose on `input/pose` into a Twist with the same linear and
angular velocity on `output/cmd_vel`; remap both to pair two turtles.
"""

from __future__ import annotations

import sys

from ros2lite.bundled.runner import run_node
from ros2lite.bundled.turtlesim.interfaces import Pose
from ros2lite.msgs.geometry_msgs.msg import Twist
from ros2lite.node import Node


class Mimic(Node):
    """turtlesim's `mimic`: one turtle copies another's velocities."""

    def __init__(self) -> None:
        super().__init__('turtle_mimic')
        self.twist_pub = self.create_publisher(Twist, 'output/cmd_vel', 1)
        self.pose_sub = self.create_subscription(Pose, 'input/pose', self.on_pose, 1)

    def on_pose(self, pose: Pose) -> None:
        """Send the leader's velocities on as a command."""
        twist = Twist()
        twist.angular.z = pose.angular_velocity
        twist.linear.x = pose.linear_velocity
        self.twist_pub.publish(twist)


def main(args: list[str] | None = None) -> int:
    """`mimic`'s entry point."""
    return run_node(Mimic, args)


if __name__ == '__main__':
    sys.exit(main())
