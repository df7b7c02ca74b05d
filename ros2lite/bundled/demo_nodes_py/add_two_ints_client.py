"""`add_two_ints_client`: waits for `add_two_ints`, asks for 2 + 3, logs the result, ends."""

from __future__ import annotations

from typing import TYPE_CHECKING

import ros2lite
from ros2lite.bundled.runner import run_main
from ros2lite.msgs.example_interfaces.srv import AddTwoInts

if TYPE_CHECKING:
    from ros2lite.node import Node
    from ros2lite.task import Future


def request_once(a: int, b: int) -> None:
    """Ask `add_two_ints` for a + b once, waiting for the server."""
    node = ros2lite.create_node('add_two_ints_client')
    client = node.create_client(AddTwoInts, 'add_two_ints')
    request = AddTwoInts.Request(a=a, b=b)
    while not client.wait_for_service(timeout_sec=1.0):
        node.get_logger().info('service not available, waiting again...')
    future = client.call_async(request)
    ros2lite.spin_until_future_complete(node, future)
    log_result(node, request, future)
    node.destroy_node()


def log_result(
    node: Node, request: AddTwoInts.Request, future: Future[AddTwoInts.Response]
) -> None:
    """Log the answer to `request`, or why there is none (both add_two_ints clients)."""
    try:
        result = future.result()
    except Exception as e:
        node.get_logger().info(f'Service call failed {e!r}')
    else:  # None only if the call was cancelled, which nothing here does
        if result is not None:
            node.get_logger().info(
                f'Result of add_two_ints: for {request.a} + {request.b} = {result.sum}'
            )


def main(args: list[str] | None = None) -> int:
    """`add_two_ints_client`'s entry point."""
    return run_main(lambda: request_once(2, 3), args)


if __name__ == '__main__':
    raise SystemExit(main())
