"""`static_turtle_tf2_broadcaster CHILD X Y Z ROLL PITCH YAW`: one static transform from
`world` to CHILD on /tf_static, sent once and latched (the tf2 tutorial "Writing a static
broadcaster")."""

from __future__ import annotations

import sys

from ros2lite.bundled.display import own_arguments
from ros2lite.bundled.runner import run_node
from ros2lite.logging import get_logger
from ros2lite.msgs.geometry_msgs.msg import TransformStamped
from ros2lite.node import Node
from ros2lite.tf2 import StaticTransformBroadcaster
from ros2lite.tf2.math import quaternion_from_rpy


class StaticFramePublisher(Node):
    """Sends CHILD's place in `world` once; late listeners still receive it."""

    def __init__(self, child: str, values: list[float]) -> None:
        super().__init__('static_turtle_tf2_broadcaster')
        self.tf_static_broadcaster = StaticTransformBroadcaster(self)
        t = TransformStamped()
        t.header.stamp = self.get_clock().now().to_msg()
        t.header.frame_id = 'world'
        t.child_frame_id = child
        tr, q = t.transform.translation, t.transform.rotation
        tr.x, tr.y, tr.z = values[:3]
        q.x, q.y, q.z, q.w = quaternion_from_rpy(*values[3:])
        self.tf_static_broadcaster.sendTransform(t)


def main(args: list[str] | None = None) -> int:
    """`static_turtle_tf2_broadcaster`'s entry point."""
    argv = own_arguments(args)
    log = get_logger('logger')
    if len(argv) != 7:
        log.info(
            'Invalid number of parameters. Usage: \n'
            '$ ros2 run turtle_tf2_py static_turtle_tf2_broadcaster '
            'child_frame_name x y z roll pitch yaw'
        )
        return 1
    if argv[0] == 'world':
        log.info('Your static turtle name cannot be "world"')
        return 2
    try:
        values = [float(v) for v in argv[1:]]
    except ValueError as e:
        log.error(f'Not a number: {e}')
        return 1
    return run_node(lambda: StaticFramePublisher(argv[0], values), args)


if __name__ == '__main__':
    sys.exit(main())
