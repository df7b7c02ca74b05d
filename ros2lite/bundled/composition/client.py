"""`composition::Client`: asks `add_two_ints` for 2 + 3 every two seconds and prints the sum."""

from __future__ import annotations

from typing import TYPE_CHECKING

from ros2lite.msgs.example_interfaces.srv import AddTwoInts
from ros2lite.node import Node
from ros2lite.task import Future

if TYPE_CHECKING:
    from typing_extensions import Unpack

    from ros2lite.node_options import NodeOptions


class Client(Node):
    """The node `Client`; answers arrive on the executor, so the timer never blocks on them."""

    def __init__(self, **kwargs: Unpack[NodeOptions]) -> None:
        super().__init__('Client', **kwargs)
        self.client = self.create_client(AddTwoInts, 'add_two_ints')
        self.timer = self.create_timer(2.0, self.on_timer)

    def on_timer(self) -> None:
        """Send the next request, if the server is there (the answer comes back asynchronously)."""
        if not self.client.wait_for_service(timeout_sec=1.0):
            self.get_logger().info('Service not available after waiting')
            return
        future = self.client.call_async(AddTwoInts.Request(a=2, b=3))
        future.add_done_callback(self.on_response)

    def on_response(self, future: Future[AddTwoInts.Response]) -> None:
        """Print the sum (or why the call failed)."""
        if future.exception() is not None:
            self.get_logger().error(f'Service call failed: {future.exception()}')
            return
        response = future.result()
        if response is not None:  # (None only for a cancelled call: nothing cancels here)
            self.get_logger().info(f'Got result: [{response.sum}]')
