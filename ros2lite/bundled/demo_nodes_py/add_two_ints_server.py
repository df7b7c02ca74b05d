"""`add_two_ints_server`: serves `add_two_ints` (example_interfaces/srv/AddTwoInts)."""

from __future__ import annotations

from ros2lite.bundled.runner import run_node
from ros2lite.msgs.example_interfaces.srv import AddTwoInts
from ros2lite.node import Node


class AddTwoIntsServer(Node):
    """demo_nodes_py's server of `add_two_ints` (`name`: the node's; introspection_service
    serves it too)."""

    def __init__(self, name: str = 'add_two_ints_server') -> None:
        super().__init__(name)
        self.srv = self.create_service(AddTwoInts, 'add_two_ints', self.add_two_ints_callback)

    def add_two_ints_callback(
        self, request: AddTwoInts.Request, response: AddTwoInts.Response
    ) -> AddTwoInts.Response:
        """Answer a + b, and log the request."""
        response.sum = request.a + request.b
        self.get_logger().info(f'Incoming request\na: {request.a} b: {request.b}')
        return response


def main(args: list[str] | None = None) -> int:
    """`add_two_ints_server`'s entry point."""
    return run_node(AddTwoIntsServer, args)


if __name__ == '__main__':
    raise SystemExit(main())
