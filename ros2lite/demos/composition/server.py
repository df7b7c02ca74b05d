"""`composition::Server`: serves `add_two_ints` (example_interfaces/srv/AddTwoInts)."""

from __future__ import annotations

from typing import Any

from ros2lite.msgs.example_interfaces.srv import AddTwoInts
from ros2lite.node import Node


class Server(Node):
    """The node `Server`."""

    def __init__(self, **kwargs: Any) -> None:
        super().__init__('Server', **kwargs)
        self.srv = self.create_service(AddTwoInts, 'add_two_ints', self.on_request)

    def on_request(self, request: Any, response: Any) -> Any:
        self.get_logger().info(f'Incoming request: [a: {request.a}, b: {request.b}]')
        response.sum = request.a + request.b
        return response
