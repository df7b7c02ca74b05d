"""`dynamic_frame_tf2_broadcaster`: a frame `carrot1` circling turtle1 at 10 m, half a turn
a second, sent on /tf ten times a second (the tf2 tutorial "Adding a frame")."""

from __future__ import annotations

import math
import sys

from ros2lite.bundled.runner import run_node
from ros2lite.msgs.geometry_msgs.msg import TransformStamped
from ros2lite.node import Node
from ros2lite.tf2 import TransformBroadcaster


class DynamicFrameBroadcaster(Node):
    """carrot1 moves around turtle1 with the clock's whole seconds."""

    def __init__(self) -> None:
        super().__init__('dynamic_frame_tf2_broadcaster')
        self.tf_broadcaster = TransformBroadcaster(self)
        self.timer = self.create_timer(0.1, self.broadcast_timer_callback)

    def broadcast_timer_callback(self) -> None:
        """Send carrot1's place for the current second."""
        now = self.get_clock().now()
        angle = now.seconds_nanoseconds()[0] * math.pi
        t = TransformStamped()
        t.header.stamp = now.to_msg()
        t.header.frame_id = 'turtle1'
        t.child_frame_id = 'carrot1'
        t.transform.translation.x = 10 * math.sin(angle)
        t.transform.translation.y = 10 * math.cos(angle)
        self.tf_broadcaster.sendTransform(t)


def main(args: list[str] | None = None) -> int:
    """`dynamic_frame_tf2_broadcaster`'s entry point."""
    return run_node(DynamicFrameBroadcaster, args)


if __name__ == '__main__':
    sys.exit(main())
