"""`teleop_twist_keyboard`: the keyboard driver robot courses use, on `cmd_vel`.

The layout, speed keys, messages and parameters (`stamped`, `frame_id`) are those of ROS 2's
teleop_twist_keyboard: every key publishes one Twist (or TwistStamped) scaled by the current
speed and turn; any other key stops; Ctrl-C quits after a last, stopping Twist.
"""

from __future__ import annotations

import sys

from ros2lite.bundled.runner import run_main
from ros2lite.msgs.geometry_msgs.msg import Twist, TwistStamped

USAGE = """
This node takes keypresses from the keyboard and publishes them
as Twist/TwistStamped messages. It works best with a US keyboard layout.
---------------------------
Moving around:
   u    i    o
   j    k    l
   m    ,    .

For Holonomic mode (strafing), hold down the shift key:
---------------------------
   U    I    O
   J    K    L
   M    <    >

t : up (+z)
b : down (-z)

anything else : stop

q/z : increase/decrease max speeds by 10%
w/x : increase/decrease only linear speed by 10%
e/c : increase/decrease only angular speed by 10%

CTRL-C to quit
"""

# key -> (x, y, z, yaw) directions
MOVES = {
    'i': (1, 0, 0, 0),
    'o': (1, 0, 0, -1),
    'j': (0, 0, 0, 1),
    'l': (0, 0, 0, -1),
    'u': (1, 0, 0, 1),
    ',': (-1, 0, 0, 0),
    '.': (-1, 0, 0, 1),
    'm': (-1, 0, 0, -1),
    'O': (1, -1, 0, 0),
    'I': (1, 0, 0, 0),
    'J': (0, 1, 0, 0),
    'L': (0, -1, 0, 0),
    'U': (1, 1, 0, 0),
    '<': (-1, 0, 0, 0),
    '>': (-1, -1, 0, 0),
    'M': (-1, 1, 0, 0),
    't': (0, 0, 1, 0),
    'b': (0, 0, -1, 0),
}
# key -> (speed factor, turn factor)
SPEEDS = {
    'q': (1.1, 1.1),
    'z': (0.9, 0.9),
    'w': (1.1, 1.0),
    'x': (0.9, 1.0),
    'e': (1.0, 1.1),
    'c': (1.0, 0.9),
}
CTRL_C = '\x03'


def vels(speed: float, turn: float) -> str:
    """The status line of the current speeds, as teleop_twist_keyboard prints it."""
    return f'currently:\tspeed {speed}\tturn {turn} '


class TeleopTwistKeyboard:
    """The `/teleop_twist_keyboard` node's state; `key()` acts on one key, False means quit."""

    def __init__(self) -> None:
        from ros2lite.node import Node

        self.node = Node('teleop_twist_keyboard')
        self.stamped = bool(self.node.declare_parameter('stamped', False).value)
        self.frame_id = str(self.node.declare_parameter('frame_id', '').value)
        if not self.stamped and self.frame_id:
            raise ValueError("'frame_id' can only be set when 'stamped' is True")
        self._msg_type: type[Twist] | type[TwistStamped] = TwistStamped if self.stamped else Twist
        self.pub = self.node.create_publisher(self._msg_type, 'cmd_vel', 10)
        self.speed = 0.5
        self.turn = 1.0
        self._status = 0
        self._direction: tuple[float, ...] = (0.0, 0.0, 0.0, 0.0)

    def publish(self, x: float, y: float, z: float, th: float) -> None:
        """Publish one (stamped) Twist in direction (x, y, z, th) at the current speeds."""
        msg = self._msg_type()
        if isinstance(msg, TwistStamped):
            msg.header.stamp = self.node.get_clock().now().to_msg()
            msg.header.frame_id = self.frame_id
            twist = msg.twist
        else:
            twist = msg
        twist.linear.x = x * self.speed
        twist.linear.y = y * self.speed
        twist.linear.z = z * self.speed
        twist.angular.z = th * self.turn
        self.pub.publish(msg)

    def key(self, key: str) -> bool:
        """Act on one key: a move key sets the direction, a speed key rescales it, anything
        else stops; every key publishes. False for Ctrl-C."""
        if key in MOVES:
            self._direction = tuple(float(v) for v in MOVES[key])
        elif key in SPEEDS:
            speed, turn = SPEEDS[key]
            self.speed *= speed
            self.turn *= turn
            print(vels(self.speed, self.turn), flush=True)
            if self._status == 14:
                print(USAGE, flush=True)
            self._status = (self._status + 1) % 15
        else:
            self._direction = (0.0, 0.0, 0.0, 0.0)
            if key == CTRL_C:
                return False
        self.publish(*self._direction)
        return True


def key_loop(teleop: TeleopTwistKeyboard) -> None:
    """Keys until Ctrl-C, the end of input or shutdown; always a stopping Twist at the end
    and the terminal restored."""
    from ros2lite.bundled.teleop.spinning import key_loop as read_keys

    try:
        read_keys(teleop.node, f'{USAGE}\n{vels(teleop.speed, teleop.turn)}', teleop.key, raw=True)
    finally:
        if teleop.node.context.ok():
            teleop.publish(0.0, 0.0, 0.0, 0.0)


def main(args: list[str] | None = None) -> int:
    """`teleop_twist_keyboard`'s entry point."""
    return run_main(lambda: key_loop(TeleopTwistKeyboard()), args)


if __name__ == '__main__':
    sys.exit(main())
