"""`talker`: publishes `Hello World: N` on `chatter` once a second, counting from 0."""

from __future__ import annotations

from ros2lite.bundled.runner import run_node
from ros2lite.msgs.std_msgs.msg import String
from ros2lite.node import Node
from ros2lite.qos import QoSProfile


class Talker(Node):
    """demo_nodes_py's talker on `chatter` (`talker_qos` is one under another name and QoS)."""

    def __init__(self, node_name: str = 'talker', qos_profile: QoSProfile | int = 10) -> None:
        super().__init__(node_name)
        self.i = 0
        self.pub = self.create_publisher(String, 'chatter', qos_profile)
        self.tmr = self.create_timer(1.0, self.timer_callback)

    def timer_callback(self) -> None:
        """Publish the next 'Hello World: N'."""
        msg = String(data=f'Hello World: {self.i}')
        self.i += 1
        self.get_logger().info(f'Publishing: "{msg.data}"')
        self.pub.publish(msg)


def main(args: list[str] | None = None) -> int:
    """`talker`'s entry point."""
    return run_node(Talker, args)


if __name__ == '__main__':
    raise SystemExit(main())
