"""An add_two_ints server (and a client) in the test process, spun on a thread."""

from __future__ import annotations

import threading
from collections.abc import Iterator
from typing import Any

import pytest

from ros2lite.executors import SingleThreadedExecutor
from ros2lite.node import Node
from tests.spinning import wait_until


@pytest.fixture
def adder(ros_context: Any) -> Iterator[Node]:
    """Node `adder` serving /add_two_ints and /math/add (and a client of /add_two_ints)."""
    from ros2lite.msgs.example_interfaces.srv import AddTwoInts

    def add(request: Any, response: Any) -> Any:
        response.sum = request.a + request.b
        return response

    node = Node('adder', context=ros_context, enable_rosout=False)
    node.create_service(AddTwoInts, 'add_two_ints', add)
    node.create_service(AddTwoInts, '/math/add', add)
    node.create_service(AddTwoInts, '/_hidden/add', add)
    node.create_client(AddTwoInts, 'add_two_ints')
    executor = SingleThreadedExecutor(context=ros_context)
    executor.add_node(node)
    thread = threading.Thread(target=executor.spin, daemon=True)
    thread.start()
    wait_until(lambda: node.count_services('/math/add') == 1)
    yield node
    executor.shutdown()
    thread.join(timeout=5)
    node.destroy_node()
