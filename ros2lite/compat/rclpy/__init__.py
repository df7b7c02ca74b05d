"""rclpy, as ros2lite provides it (``ros2lite env``): the names code written for rclpy imports,
each a thin face over ros2lite's own library. Nothing is implemented here; see
:mod:`ros2lite` for the behaviour and the README section "Run code written for rclpy" for what
is covered.
"""

from __future__ import annotations

import importlib

from ros2lite import (
    create_node,
    get_global_executor,
    init,
    ok,
    shutdown,
    spin,
    spin_once,
    spin_until_future_complete,
    try_shutdown,
)
from ros2lite.context import Context
from ros2lite.context import default_context as get_default_context
from ros2lite.parameter import Parameter
from ros2lite.task import Future

from . import context, exceptions, node, qos, utilities

__all__ = [
    'Context',
    'Future',
    'Parameter',
    'context',
    'create_node',
    'exceptions',
    'get_default_context',
    'get_global_executor',
    'init',
    'node',
    'ok',
    'qos',
    'shutdown',
    'spin',
    'spin_once',
    'spin_until_future_complete',
    'try_shutdown',
    'utilities',
]


def __getattr__(name: str) -> object:
    """`rclpy.<module>` without importing it first, as rclpy's own imports make possible."""
    if name.startswith('_'):
        raise AttributeError(name)
    try:
        return importlib.import_module(f'{__name__}.{name}')
    except ModuleNotFoundError as e:
        if e.name != f'{__name__}.{name}':
            raise
        raise AttributeError(f"module 'rclpy' has no attribute '{name}'") from None
