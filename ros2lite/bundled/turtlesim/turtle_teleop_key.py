"""`turtle_teleop_key`: drive turtle1 from the keyboard, as turtlesim's teleop does.

Arrow keys publish one Twist each on `turtle1/cmd_vel` (2.0 m/s, 2.0 rad/s: the
`scale_linear` and `scale_angular` parameters); the keys around F send `rotate_absolute` goals
to the orientation they sit at from F, F cancels the goal, Q quits. Its node is
`/teleop_turtle`.
"""

from __future__ import annotations

import sys
from typing import TYPE_CHECKING

from ros2lite.bundled.runner import run_main

if TYPE_CHECKING:
    from ros2lite.action import ClientGoalHandle
    from ros2lite.bundled.turtlesim.interfaces import RotateAbsolute
    from ros2lite.task import Future

    _Handle = ClientGoalHandle[RotateAbsolute.Goal, RotateAbsolute.Result, RotateAbsolute.Feedback]

INSTRUCTIONS = (
    'Reading from keyboard\n'
    '---------------------------\n'
    'Use arrow keys to move the turtle.\n'
    "Use g|b|v|c|d|e|r|t keys to rotate to absolute orientations. 'f' to cancel a rotation.\n"
    "'q' to quit."
)

# key -> (linear, angular) units, scaled by the parameters
MOVES = {'up': (1.0, 0.0), 'down': (-1.0, 0.0), 'left': (0.0, 1.0), 'right': (0.0, -1.0)}
# key -> absolute orientation: each letter's direction as seen from F on a US keyboard
ROTATIONS = {
    'g': 0.0,
    't': 0.7854,
    'r': 1.5708,
    'e': 2.3562,
    'd': 3.1416,
    'c': -2.3562,
    'v': -1.5708,
    'b': -0.7854,
}


class TeleopTurtle:
    """The `/teleop_turtle` node's parts; `key()` acts on one key, False means quit."""

    def __init__(self) -> None:
        from ros2lite.action import ActionClient
        from ros2lite.bundled.turtlesim.interfaces import RotateAbsolute
        from ros2lite.msgs.geometry_msgs.msg import Twist
        from ros2lite.node import Node

        self.node = Node('teleop_turtle')
        self.scale_angular = float(self.node.declare_parameter('scale_angular', 2.0).value)
        self.scale_linear = float(self.node.declare_parameter('scale_linear', 2.0).value)
        self._twist = Twist
        self._rotate = RotateAbsolute
        self.twist_pub = self.node.create_publisher(Twist, 'turtle1/cmd_vel', 1)
        self.rotate_client = ActionClient(self.node, RotateAbsolute, 'turtle1/rotate_absolute')
        self.goal_handle: _Handle | None = None

    def key(self, key: str) -> bool:
        """Act on one key (move, rotate, cancel); False for Q (quit)."""
        key = key.lower() if len(key) == 1 else key
        if key == 'q':
            return False
        if key in MOVES:
            linear, angular = MOVES[key]
            twist = self._twist()
            twist.linear.x = self.scale_linear * linear
            twist.angular.z = self.scale_angular * angular
            self.twist_pub.publish(twist)
        elif key in ROTATIONS:
            self.send_goal(ROTATIONS[key])
        elif key == 'f':
            self.cancel_goal()
        return True

    def send_goal(self, theta: float) -> None:
        """Ask rotate_absolute to turn turtle1 to `theta`."""
        future = self.rotate_client.send_goal_async(self._rotate.Goal(theta=theta))
        future.add_done_callback(self._on_goal_response)

    def _on_goal_response(self, future: Future[_Handle]) -> None:
        self.node.get_logger().debug('Goal response received')
        self.goal_handle = future.result()

    def cancel_goal(self) -> None:
        """Cancel the last rotate goal, if any."""
        if self.goal_handle is not None:
            self.node.get_logger().debug('Sending cancel request')
            self.goal_handle.cancel_goal_async()


def key_loop(teleop: TeleopTurtle) -> None:
    """Read keys until Q, the end of input, or shutdown (the terminal restored either way)."""
    from ros2lite.bundled.teleop.spinning import key_loop as read_keys

    read_keys(teleop.node, INSTRUCTIONS, teleop.key)


def main(args: list[str] | None = None) -> int:
    """`turtle_teleop_key`'s entry point."""
    return run_main(lambda: key_loop(TeleopTurtle()), args)


if __name__ == '__main__':
    sys.exit(main())
