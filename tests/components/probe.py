"""A component for the container tests: shows what the container handed its node."""

from __future__ import annotations

from typing import Any

from ros2lite.node import Node


class Probe(Node):
    """Node `probe`: a `greeting` parameter and a publisher on `chatter` (for remaps)."""

    def __init__(self, **kwargs: Any) -> None:
        super().__init__('probe', **kwargs)
        self.declare_parameter('greeting', 'hello')
        self.pub = self.create_publisher('std_msgs/msg/String', 'chatter', 10)


class Broken(Node):
    """Fails while being built."""

    def __init__(self, **kwargs: Any) -> None:
        raise RuntimeError('no hardware here')


def not_a_node(**kwargs: Any) -> object:
    """Callable, but builds no node."""
    return object()
