"""`composition::Server`: serves `add_two_ints` (example_interfaces/srv/AddTwoInts)."""

from __future__ import annotations

from typing import TYPE_CHECKING

from ros2lite.msgs.example_interfaces.srv import AddTwoInts
from ros2lite.node import Node

if TYPE_CHECKING:
    from typing_extensions import Unpack

    from ros2lite.node_options import NodeOptions


class Server(Node):
    """The node `Server`."""

    def __init__(self, **kwargs: Unpack[NodeOptions]) -> None:
        super().__init__('Server', **kwargs)
        self.srv = self.create_service(AddTwoInts, 'add_two_ints', self.on_request)

    def on_request(
        self, request: AddTwoInts.Request, response: AddTwoInts.Response
    ) -> AddTwoInts.Response:
        """Answer a + b."""
        self.get_logger().info(f'Incoming request: [a: {request.a}, b: {request.b}]')
        response.sum = request.a + request.b
        return response
