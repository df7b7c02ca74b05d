"""`composition::Listener`: prints what arrives on `chatter`."""

from __future__ import annotations

from typing import TYPE_CHECKING

from ros2lite.msgs.std_msgs.msg import String
from ros2lite.node import Node

if TYPE_CHECKING:
    from typing_extensions import Unpack

    from ros2lite.node_options import NodeOptions


class Listener(Node):
    """The node `listener`."""

    def __init__(self, **kwargs: Unpack[NodeOptions]) -> None:
        super().__init__('listener', **kwargs)
        self.sub = self.create_subscription(String, 'chatter', self.on_message, 10)

    def on_message(self, msg: String) -> None:
        """Log what was heard."""
        self.get_logger().info(f'I heard: [{msg.data}]')
