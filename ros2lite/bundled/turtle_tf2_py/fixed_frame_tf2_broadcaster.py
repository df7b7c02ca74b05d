"""`fixed_frame_tf2_broadcaster`: a frame `carrot1` held 2 m to turtle1's left, sent on /tf
ten times a second (the tf2 tutorial "Adding a frame")."""

from __future__ import annotations

import sys

from ros2lite.bundled.runner import run_node
from ros2lite.msgs.geometry_msgs.msg import TransformStamped
from ros2lite.node import Node
from ros2lite.tf2 import TransformBroadcaster


class FixedFrameBroadcaster(Node):
    """carrot1 rides along with turtle1, at (0, 2) in turtle1's frame."""

    def __init__(self) -> None:
        super().__init__('fixed_frame_tf2_broadcaster')
        self.tf_broadcaster = TransformBroadcaster(self)
        self.timer = self.create_timer(0.1, self.broadcast_timer_callback)

    def broadcast_timer_callback(self) -> None:
        """Send carrot1's (unchanging) place, stamped now."""
        t = TransformStamped()
        t.header.stamp = self.get_clock().now().to_msg()
        t.header.frame_id = 'turtle1'
        t.child_frame_id = 'carrot1'
        t.transform.translation.y = 2.0
        self.tf_broadcaster.sendTransform(t)


def main(args: list[str] | None = None) -> int:
    """`fixed_frame_tf2_broadcaster`'s entry point."""
    return run_node(FixedFrameBroadcaster, args)


if __name__ == '__main__':
    sys.exit(main())
