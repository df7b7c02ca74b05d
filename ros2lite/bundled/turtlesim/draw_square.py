"""`draw_square`: resets turtlesim, then drives turtle1 round a 2 m square for ever.

turtlesim's tutorial node (`/draw_square`): every 16 ms it compares the pose with its goal —
forward at 1 m/s until 2 m on, stop, turn at 0.4 rad/s through a quarter turn, stop — and
logs each new goal.
"""

from __future__ import annotations

import math
import sys

from ros2lite.bundled.runner import run_node
from ros2lite.bundled.turtlesim.interfaces import Pose
from ros2lite.bundled.turtlesim.sim import f32
from ros2lite.msgs.geometry_msgs.msg import Twist
from ros2lite.msgs.std_srvs.srv import Empty
from ros2lite.node import Node

PI = 3.141592  # the tutorial's own
FORWARD, STOP_FORWARD, TURN, STOP_TURN = range(4)


class DrawSquare(Node):
    """turtlesim's `draw_square` node: turtle1 round a 2 m square."""

    def __init__(self) -> None:
        super().__init__('draw_square')
        self.twist_pub = self.create_publisher(Twist, 'turtle1/cmd_vel', 10)
        self.pose_sub = self.create_subscription(Pose, 'turtle1/pose', self.on_pose, 10)
        self.reset_client = self.create_client(Empty, 'reset')
        self.timer = self.create_timer(0.016, self.on_timer)
        self.reset_done = self.reset_client.call_async(Empty.Request())
        self.pose: Pose | None = None  # once one came after the reset
        self.goal = Pose()
        self.state = FORWARD
        self.first_goal_set = False

    def on_pose(self, pose: Pose) -> None:
        """Keep the latest pose (once the reset is done)."""
        if self.reset_done.done():  # poses from before the reset are of the old turtle1
            self.pose = pose

    def reached_goal(self, p: Pose) -> bool:
        """Whether the pose is at the goal (position and heading)."""
        g = self.goal
        return abs(p.x - g.x) < 0.1 and abs(p.y - g.y) < 0.1 and abs(p.theta - g.theta) < 0.01

    def stopped(self, p: Pose) -> bool:
        """Whether the turtle stands still."""
        return p.angular_velocity < 0.0001 and p.linear_velocity < 0.0001

    def print_goal(self) -> None:
        """Log the new goal, as draw_square does."""
        g = self.goal
        self.get_logger().info(f'New goal [{g.x:f} {g.y:f}, {g.theta:f}]')

    def command(self, linear: float, angular: float) -> None:
        """Publish one velocity command."""
        twist = Twist()
        twist.linear.x = linear
        twist.angular.z = angular
        self.twist_pub.publish(twist)

    def goal_ahead(self, p: Pose) -> None:
        """Set the goal 2 m ahead of the turtle."""
        self.goal.x = f32(math.cos(p.theta) * 2 + p.x)
        self.goal.y = f32(math.sin(p.theta) * 2 + p.y)
        self.goal.theta = p.theta

    def on_timer(self) -> None:
        """One 16 ms step of the square's state machine."""
        pose = self.pose
        if pose is None:
            return
        if not self.first_goal_set:
            self.first_goal_set = True
            self.state = FORWARD
            self.goal_ahead(pose)
            self.print_goal()
        if self.state == FORWARD:
            if self.reached_goal(pose):
                self.state = STOP_FORWARD
                self.command(0.0, 0.0)
            else:
                self.command(1.0, 0.0)
        elif self.state == STOP_FORWARD:
            if self.stopped(pose):
                self.get_logger().info('Reached goal')
                self.state = TURN
                self.goal.x = pose.x
                self.goal.y = pose.y
                theta = math.fmod(pose.theta + PI / 2.0, 2.0 * PI)
                if theta >= PI:  # into [-pi, pi)
                    theta -= 2.0 * PI
                self.goal.theta = f32(theta)
                self.print_goal()
            else:
                self.command(0.0, 0.0)
        elif self.state == TURN:
            if self.reached_goal(pose):
                self.state = STOP_TURN
                self.command(0.0, 0.0)
            else:
                self.command(0.0, 0.4)
        elif self.stopped(pose):
            self.get_logger().info('Reached goal')
            self.state = FORWARD
            self.goal_ahead(pose)
            self.print_goal()
        else:
            self.command(0.0, 0.0)


def main(args: list[str] | None = None) -> int:
    """`draw_square`'s entry point."""
    return run_node(DrawSquare, args)


if __name__ == '__main__':
    sys.exit(main())
