"""`composition::Talker`: publishes `Hello World: N` on `chatter` every second, from 1."""

from __future__ import annotations

from typing import TYPE_CHECKING

from ros2lite.msgs.std_msgs.msg import String
from ros2lite.node import Node

if TYPE_CHECKING:
    from typing_extensions import Unpack

    from ros2lite.node_options import NodeOptions


class Talker(Node):
    """The node `talker`."""

    def __init__(self, **kwargs: Unpack[NodeOptions]) -> None:
        super().__init__('talker', **kwargs)
        self.count = 0
        self.pub = self.create_publisher(String, 'chatter', 10)
        self.timer = self.create_timer(1.0, self.on_timer)

    def on_timer(self) -> None:
        """Publish the next 'Hello World: N'."""
        self.count += 1
        msg = String(data=f'Hello World: {self.count}')
        self.get_logger().info(f"Publishing: '{msg.data}'")
        self.pub.publish(msg)
