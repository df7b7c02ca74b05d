"""`teleop_twist_keyboard` through a pseudo-terminal: its help text, one Twist per key on
/cmd_vel with the current speed and turn, the speed keys, and Ctrl-C (a key in its raw
mode) ending with a stopping Twist and the terminal given back."""

from __future__ import annotations

import termios
import time
from typing import Any

from ros2lite.qos import QoSProfile
from tests.bundled.ptyproc import PtyProcess, ros2lite_argv
from tests.spinning import Listener


def test_keys_publish_twists(ros_context: Any) -> None:
    listener = Listener(ros_context, '/cmd_vel', 'geometry_msgs/msg/Twist', QoSProfile(depth=10))
    proc = PtyProcess(ros2lite_argv('run', 'teleop_twist_keyboard', 'teleop_twist_keyboard'))
    try:
        proc.expect(r'currently:\tspeed 0\.5\tturn 1\.0 ')
        assert 'Moving around:\r\n   u    i    o\r\n   j    k    l\r\n   m    ,    .' in (
            proc.output
        )
        deadline = time.monotonic() + 10
        while listener.node.count_publishers('/cmd_vel') < 1:
            assert time.monotonic() < deadline
            time.sleep(0.05)

        def next_twist(key: str) -> Any:
            count = len(listener.messages)
            proc.send(key)
            deadline = time.monotonic() + 10
            while len(listener.messages) <= count:
                assert time.monotonic() < deadline, key
                time.sleep(0.02)
            return listener.messages[-1]

        t = next_twist('i')
        assert (t.linear.x, t.angular.z) == (0.5, 0.0)
        t = next_twist('u')
        assert (t.linear.x, t.angular.z) == (0.5, 1.0)
        t = next_twist('q')  # 10 % faster, same direction
        assert (t.linear.x, t.angular.z) == (0.55, 1.1)
        proc.expect(r'currently:\tspeed 0\.55\tturn 1\.1 ')
        t = next_twist('J')  # holonomic: strafe left
        assert (t.linear.x, t.linear.y) == (0.0, 0.55)
        t = next_twist('k')  # anything else stops
        assert (t.linear.x, t.linear.y, t.angular.z) == (0.0, 0.0, 0.0)
        next_twist('i')
        t = next_twist('\x03')  # Ctrl-C: one last, stopping Twist
        assert t.linear.x == 0.0
        assert proc.wait() == 0
        lflag = proc.attrs()[3]
        assert lflag & termios.ECHO and lflag & termios.ICANON and lflag & termios.ISIG
        assert 'Traceback' not in proc.output
    finally:
        proc.close()
        listener.stop()
