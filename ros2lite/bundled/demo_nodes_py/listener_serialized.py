"""`listener_serialized` (node `serialized_subscriber`): subscribes to `chatter` for the raw
CDR bytes, not a decoded `std_msgs/String`, and logs them as Python shows bytes."""

from __future__ import annotations

from ros2lite.bundled.runner import run_node
from ros2lite.msgs.std_msgs.msg import String
from ros2lite.node import Node


class SerializedSubscriber(Node):
    """Logs each message on `chatter` as its serialized bytes."""

    def __init__(self) -> None:
        super().__init__('serialized_subscriber')
        self.subscription = self.create_subscription(
            String, 'chatter', self.listener_callback, 10, raw=True
        )

    def listener_callback(self, msg: bytes) -> None:
        """Log the bytes that arrived."""
        self.get_logger().info(f'I heard: "{bytes(msg)!r}"')


def main(args: list[str] | None = None) -> int:
    """`listener_serialized`'s entry point."""
    return run_node(SerializedSubscriber, args)


if __name__ == '__main__':
    raise SystemExit(main())
