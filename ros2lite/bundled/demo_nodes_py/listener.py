"""`listener`: logs every `std_msgs/String` that arrives on `chatter`."""

from __future__ import annotations

from ros2lite.bundled.runner import run_node
from ros2lite.msgs.std_msgs.msg import String
from ros2lite.node import Node
from ros2lite.qos import QoSProfile


class Listener(Node):
    """demo_nodes_py's listener of `chatter` (`listener_qos` is one under another name and
    QoS)."""

    def __init__(self, node_name: str = 'listener', qos_profile: QoSProfile | int = 10) -> None:
        super().__init__(node_name)
        self.sub = self.create_subscription(String, 'chatter', self.chatter_callback, qos_profile)

    def chatter_callback(self, msg: String) -> None:
        """Log what was heard."""
        self.get_logger().info(f'I heard: [{msg.data}]')


def main(args: list[str] | None = None) -> int:
    """`listener`'s entry point."""
    return run_node(Listener, args)


if __name__ == '__main__':
    raise SystemExit(main())
