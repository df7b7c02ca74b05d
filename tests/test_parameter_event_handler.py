"""ParameterEventHandler: callbacks for another node's parameter changes, from the events it
publishes on /parameter_events."""

from __future__ import annotations

from typing import Any

import pytest

from ros2lite.executors import SingleThreadedExecutor
from ros2lite.node import Node
from ros2lite.parameter import Parameter
from ros2lite.parameter_event_handler import ParameterEventHandler
from tests.spinning import spin_until


def test_parameter_and_event_callbacks(ros_context: Any) -> None:
    watcher = Node('watcher', namespace='/team', context=ros_context)
    target = Node('target', namespace='/team', context=ros_context)
    target.declare_parameter('gain', 1.0)
    handler = ParameterEventHandler(watcher)
    gains: list[float] = []
    events: list[str] = []
    order: list[str] = []
    first = handler.add_parameter_callback('gain', 'target', lambda p: order.append('first'))

    def second(parameter: Any) -> None:
        order.append('second')
        gains.append(parameter.value.double_value)

    handler.add_parameter_callback('gain', 'target', second)
    handler.add_parameter_event_callback(lambda e: events.append(e.node))
    executor = SingleThreadedExecutor(context=ros_context)
    executor.add_node(watcher)

    def changed() -> bool:
        target.set_parameters([Parameter('gain', value=2.5)])  # again, until one is heard
        executor.spin_once(timeout_sec=0.05)
        return bool(gains)

    spin_until(executor, changed, timeout=10)
    assert gains[0] == 2.5 and '/team/target' in events
    assert (order and order[-1] == 'first') or order == []  # newest callback first
    handler.remove_parameter_callback(first)
    with pytest.raises(RuntimeError):
        handler.remove_parameter_callback(first)
    assert handler._resolve_path() == '/team/watcher'
    assert handler._resolve_path('/elsewhere') == '/elsewhere'
    handler.destroy()
