"""`lifecycle_talker`: the managed node `lc_talker`, publishing `Lifecycle HelloWorld #N` on
`lifecycle_chatter` once a second — but only while active.

Drive it with `ros2lite lifecycle set /lc_talker configure`, then `activate`, `deactivate`,
`cleanup`, `shutdown`; the timer runs from configure on, so an inactive talker says it is not
publishing.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from ros2lite.bundled.runner import run_node
from ros2lite.lifecycle import LifecycleNode, LifecyclePublisher, State, TransitionCallbackReturn
from ros2lite.msgs.std_msgs.msg import String
from ros2lite.timer import Timer

if TYPE_CHECKING:
    from typing_extensions import Unpack

    from ros2lite.node_options import NodeOptions


class LifecycleTalker(LifecycleNode):
    """The demo's talker: publisher and timer exist between configure and cleanup."""

    def __init__(self, node_name: str = 'lc_talker', **kwargs: Unpack[NodeOptions]) -> None:
        self._count = 0
        self._pub: LifecyclePublisher | None = None
        self._timer: Timer | None = None
        super().__init__(node_name, **kwargs)

    def publish(self) -> None:
        """Timer callback: say what happens to the next message, then publish it."""
        msg = String(data=f'Lifecycle HelloWorld #{self._count}')
        self._count += 1
        if self._pub is None or not self._pub.is_activated:
            self.get_logger().info('Lifecycle publisher is inactive. Messages are not published.')
        else:
            self.get_logger().info(f'Lifecycle publisher is active. Publishing: [{msg.data}]')
        if self._pub is not None:
            self._pub.publish(msg)

    def on_configure(self, state: State) -> TransitionCallbackReturn:
        """Make the lifecycle publisher and the 1 s timer."""
        self._pub = self.create_lifecycle_publisher(String, 'lifecycle_chatter', 10)
        self._timer = self.create_timer(1.0, self.publish)
        self.get_logger().info('on_configure() is called.')
        return TransitionCallbackReturn.SUCCESS

    def on_activate(self, state: State) -> TransitionCallbackReturn:
        """Log, then activate the publisher."""
        self.get_logger().info('on_activate() is called.')
        return super().on_activate(state)

    def on_deactivate(self, state: State) -> TransitionCallbackReturn:
        """Log, then deactivate the publisher."""
        self.get_logger().info('on_deactivate() is called.')
        return super().on_deactivate(state)

    def _release(self) -> None:
        if self._timer is not None:
            self.destroy_timer(self._timer)
            self._timer = None
        if self._pub is not None:
            self.destroy_lifecycle_publisher(self._pub)
            self._pub = None

    def on_cleanup(self, state: State) -> TransitionCallbackReturn:
        """Drop the publisher and the timer."""
        self._release()
        self.get_logger().info('on_cleanup() is called.')
        return TransitionCallbackReturn.SUCCESS

    def on_shutdown(self, state: State) -> TransitionCallbackReturn:
        """Drop the publisher and the timer before finalizing."""
        self._release()
        self.get_logger().info('on_shutdown() is called.')
        return TransitionCallbackReturn.SUCCESS


def main(args: list[str] | None = None) -> int:
    """`lifecycle_talker`'s entry point."""
    return run_node(LifecycleTalker, args)


if __name__ == '__main__':
    raise SystemExit(main())
