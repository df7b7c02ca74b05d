"""The logger services of a node (`enable_logger_service=True`): levels read and set from
another node, invalid levels refused one by one."""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any

import pytest

from ros2lite import logging as rlog
from ros2lite.executors import SingleThreadedExecutor
from ros2lite.interfaces import get_interface
from ros2lite.node import Node

GetLevels = get_interface('rcl_interfaces/srv/GetLoggerLevels')
SetLevels = get_interface('rcl_interfaces/srv/SetLoggerLevels')
Level = get_interface('rcl_interfaces/msg/LoggerLevel')


@pytest.fixture(autouse=True)
def clean_levels() -> Iterator[None]:
    saved = dict(rlog._levels)
    yield
    rlog._levels.clear()
    rlog._levels.update(saved)


def test_levels_through_the_services(ros_context: Any) -> None:
    served = Node('with_levels', context=ros_context, enable_logger_service=True)
    assert not Node('without', context=ros_context).count_services('/without/get_logger_levels')
    caller = Node('level_caller', context=ros_context)
    executor = SingleThreadedExecutor(context=ros_context)
    executor.add_node(served)
    executor.add_node(caller)

    def call(srv_type: Any, name: str, request: Any) -> Any:
        client = caller.create_client(srv_type, name)
        assert client.wait_for_service(10)
        future = client.call_async(request)
        executor.spin_until_future_complete(future, 10)
        return future.result()

    request = SetLevels.Request(levels=[Level(name='rcl', level=10), Level(name='x', level=22)])
    results = call(SetLevels, '/with_levels/set_logger_levels', request).results
    assert [(r.successful, r.reason) for r in results] == [
        (True, ''),
        (False, 'Failed reason: Invalid logger level.'),
    ]
    assert rlog.get_logger_effective_level('rcl') == rlog.LoggingSeverity.DEBUG
    got = call(GetLevels, '/with_levels/get_logger_levels', GetLevels.Request(names=['rcl']))
    assert [(lv.name, lv.level) for lv in got.levels] == [('rcl', 10)]
    # a logger nobody set answers UNSET (0), not the default it follows, as rclpy's service
    got = call(GetLevels, '/with_levels/get_logger_levels', GetLevels.Request(names=['never']))
    assert [(lv.name, lv.level) for lv in got.levels] == [('never', 0)]
