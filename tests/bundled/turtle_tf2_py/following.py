"""Watching turtle2 follow turtle1: both poses from a node of the test, and the distance
between them until it is small."""

from __future__ import annotations

import math
from typing import Any

from ros2lite.executors import SingleThreadedExecutor
from ros2lite.msgs.turtlesim.msg import Pose
from ros2lite.node import Node
from tests.spinning import spin_until


def assert_turtle2_follows_turtle1(
    context: Any, timeout: float = 60.0, offset: tuple[float, float] = (0.0, 0.0)
) -> list[float]:
    """The distance from turtle2 to turtle1 (or to the point `offset` in turtle1's frame)
    falls from turtle2's spawn point, over 3 m away, to under 1 m; returns the distances
    seen, one per turtle2 pose."""
    node = Node('follow_watcher', context=context)
    poses: dict[str, Pose] = {}
    distances: list[float] = []

    def on_pose(name: str) -> Any:
        def store(msg: Pose) -> None:
            poses[name] = msg
            if name == 'turtle2' and 'turtle1' in poses:
                leader = poses['turtle1']
                c, s = math.cos(leader.theta), math.sin(leader.theta)
                x = leader.x + c * offset[0] - s * offset[1]
                y = leader.y + s * offset[0] + c * offset[1]
                distances.append(math.hypot(msg.x - x, msg.y - y))

        return store

    for name in ('turtle1', 'turtle2'):
        node.create_subscription(Pose, f'/{name}/pose', on_pose(name), 10)
    executor = SingleThreadedExecutor(context=context)
    executor.add_node(node)
    try:
        spin_until(executor, lambda: distances, timeout=timeout)
        assert distances[0] > 3.0, distances[:5]  # spawned at (4, 2), turtle1 at the centre
        spin_until(executor, lambda: distances[-1] < 1.0, timeout=timeout)
    finally:
        executor.shutdown()
        node.destroy_node()
    return distances
