"""`turtle_tf2_listener`: spawns turtle2, then once a second looks up where the
`target_frame` (turtle1) is as seen from turtle2 and steers turtle2 towards it (the tf2
tutorial's listener)."""

from __future__ import annotations

import math
import sys

from ros2lite.bundled.runner import run_node
from ros2lite.msgs.geometry_msgs.msg import Twist
from ros2lite.msgs.turtlesim.srv import Spawn
from ros2lite.node import Node
from ros2lite.task import Future
from ros2lite.tf2 import Buffer, TransformException, TransformListener
from ros2lite.time import Time

_FORWARD_GAIN = 0.5
_TURN_GAIN = 1.0


class FrameListener(Node):
    """Steers turtle2 towards the target frame."""

    def __init__(self) -> None:
        super().__init__('turtle_tf2_frame_listener')
        self.target_frame = str(self.declare_parameter('target_frame', 'turtle1').value)
        self.tf_buffer = Buffer()
        self.tf_listener = TransformListener(self.tf_buffer, self)
        self.spawner = self.create_client(Spawn, 'spawn')
        self.spawn_result: Future[Spawn.Response] | None = None
        self.turtle_spawned = False
        self.publisher = self.create_publisher(Twist, 'turtle2/cmd_vel', 1)
        self.timer = self.create_timer(1.0, self.on_timer)

    def on_timer(self) -> None:
        """Spawn first; once turtle2 exists, one steering command a second."""
        if self.spawn_result is None:
            if not self.spawner.service_is_ready():
                self.get_logger().info('Service is not ready')
                return
            self.spawn_result = self.spawner.call_async(
                Spawn.Request(name='turtle2', x=4.0, y=2.0, theta=0.0)
            )
            return
        if not self.turtle_spawned:
            if not self.spawn_result.done():
                self.get_logger().info('Spawn is not finished')
                return
            response = self.spawn_result.result()
            name = response.name if response is not None else 'turtle2'
            self.get_logger().info(f'Successfully spawned {name}')
            self.turtle_spawned = True
            return
        try:
            t = self.tf_buffer.lookup_transform('turtle2', self.target_frame, Time())
        except TransformException as ex:
            self.get_logger().info(f'Could not transform turtle2 to {self.target_frame}: {ex}')
            return
        x, y = t.transform.translation.x, t.transform.translation.y
        msg = Twist()
        msg.angular.z = _TURN_GAIN * math.atan2(y, x)
        msg.linear.x = _FORWARD_GAIN * math.hypot(x, y)
        self.publisher.publish(msg)


def main(args: list[str] | None = None) -> int:
    """`turtle_tf2_listener`'s entry point."""
    return run_node(FrameListener, args)


if __name__ == '__main__':
    sys.exit(main())
