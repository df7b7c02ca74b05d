"""`lifecycle_listener`: the node `listener`, printing what `lc_talker` publishes on
`lifecycle_chatter` and every state change it announces on `/lc_talker/transition_event`."""

from __future__ import annotations

from typing import TYPE_CHECKING

from ros2lite.bundled.runner import run_node
from ros2lite.msgs.lifecycle_msgs.msg import TransitionEvent
from ros2lite.msgs.std_msgs.msg import String
from ros2lite.node import Node

if TYPE_CHECKING:
    from typing_extensions import Unpack

    from ros2lite.node_options import NodeOptions


class LifecycleListener(Node):
    """Logs data and transitions of the lifecycle talker."""

    def __init__(self, node_name: str = 'listener', **kwargs: Unpack[NodeOptions]) -> None:
        super().__init__(node_name, **kwargs)
        self.create_subscription(String, 'lifecycle_chatter', self.data_callback, 10)
        self.create_subscription(
            TransitionEvent, '/lc_talker/transition_event', self.notification_callback, 10
        )

    def data_callback(self, msg: String) -> None:
        """Log the data."""
        self.get_logger().info(f'data_callback: {msg.data}')

    def notification_callback(self, msg: TransitionEvent) -> None:
        """Log the transition."""
        self.get_logger().info(
            f'notify callback: Transition from state {msg.start_state.label} to '
            f'{msg.goal_state.label}'
        )


def main(args: list[str] | None = None) -> int:
    """`lifecycle_listener`'s entry point."""
    return run_node(LifecycleListener, args)


if __name__ == '__main__':
    raise SystemExit(main())
