"""`introspection_client`: asks `add_two_ints` for 2 + 3 every half second; its introspection
follows its `client_configure_introspection` parameter (`disabled`, `metadata`, `contents`)."""

from __future__ import annotations

from ros2lite.bundled.demo_nodes_py.introspection_service import follow_parameter
from ros2lite.bundled.runner import run_node
from ros2lite.msgs.example_interfaces.srv import AddTwoInts
from ros2lite.node import Node
from ros2lite.task import Future


class IntrospectionClientNode(Node):
    """One request at a time: the next goes out once the last one has been answered."""

    def __init__(self) -> None:
        super().__init__('introspection_client')
        self.cli = self.create_client(AddTwoInts, 'add_two_ints')
        follow_parameter(self, 'client_configure_introspection', self.cli.configure_introspection)
        self.future: Future[AddTwoInts.Response] | None = None
        self.timer = self.create_timer(0.5, self.timer_callback)

    def timer_callback(self) -> None:
        """Log the answer to the last request, or send the next one."""
        if not self.cli.service_is_ready():
            return
        if self.future is None:
            self.future = self.cli.call_async(AddTwoInts.Request(a=2, b=3))
            return
        if not self.future.done():
            return
        response = self.future.result() if self.future.exception() is None else None
        if response is not None:
            self.get_logger().info(f'Result of add_two_ints: {response.sum}')
        else:
            self.get_logger().error(f'Exception calling service: {self.future.exception()!r}')
        self.future = None


def main(args: list[str] | None = None) -> int:
    """`introspection_client`'s entry point."""
    return run_node(IntrospectionClientNode, args)


if __name__ == '__main__':
    raise SystemExit(main())
