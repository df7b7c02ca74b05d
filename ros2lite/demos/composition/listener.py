"""`composition::Listener`: prints what arrives on `chatter`."""

from __future__ import annotations

from typing import Any

from ros2lite.msgs.std_msgs.msg import String
from ros2lite.node import Node


class Listener(Node):
    """The node `listener`."""

    def __init__(self, **kwargs: Any) -> None:
        super().__init__('listener', **kwargs)
        self.sub = self.create_subscription(String, 'chatter', self.on_message, 10)

    def on_message(self, msg: Any) -> None:
        self.get_logger().info(f'I heard: [{msg.data}]')
