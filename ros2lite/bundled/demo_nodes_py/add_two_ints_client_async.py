"""`add_two_ints_client_async`: the same as `add_two_ints_client`, asking for 41 + 1 and
spinning the node itself until the future is done."""

from __future__ import annotations

import ros2lite
from ros2lite.bundled.demo_nodes_py.add_two_ints_client import log_result
from ros2lite.bundled.runner import run_main
from ros2lite.msgs.example_interfaces.srv import AddTwoInts


def request_async() -> None:
    """Ask `add_two_ints` for 41 + 1, spinning until the answer comes."""
    node = ros2lite.create_node('add_two_ints_client')
    client = node.create_client(AddTwoInts, 'add_two_ints')
    while not client.wait_for_service(timeout_sec=1.0):
        print('service not available, waiting again...', flush=True)
    request = AddTwoInts.Request(a=41, b=1)
    future = client.call_async(request)
    while ros2lite.ok():
        ros2lite.spin_once(node)
        if future.done():
            log_result(node, request, future)
            break
    node.destroy_node()


def main(args: list[str] | None = None) -> int:
    """`add_two_ints_client_async`'s entry point."""
    return run_main(request_async, args)


if __name__ == '__main__':
    raise SystemExit(main())
