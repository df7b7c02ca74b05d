"""Managed (lifecycle) nodes, with rclpy.lifecycle's names.

`Node`, `Publisher` and `State` are the short aliases rclpy offers for `LifecycleNode`,
`LifecyclePublisher` and `LifecycleState`::

    from ros2lite.lifecycle import Node, State, TransitionCallbackReturn

`ros2lite.lifecycle.remote` drives other nodes' lifecycles (what `ros2lite lifecycle` uses).
"""

from __future__ import annotations

from ros2lite.lifecycle.managed_entity import ManagedEntity, SimpleManagedEntity
from ros2lite.lifecycle.node import LifecycleNode, LifecycleNodeMixin
from ros2lite.lifecycle.publisher import LifecyclePublisher
from ros2lite.lifecycle.state_machine import (
    InvalidTransitionError,
    LifecycleState,
    TransitionCallbackReturn,
)

Node = LifecycleNode
Publisher = LifecyclePublisher
State = LifecycleState

__all__ = [
    'InvalidTransitionError',
    'LifecycleNode',
    'LifecycleNodeMixin',
    'LifecyclePublisher',
    'LifecycleState',
    'ManagedEntity',
    'Node',
    'Publisher',
    'SimpleManagedEntity',
    'State',
    'TransitionCallbackReturn',
]
