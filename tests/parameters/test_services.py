"""The six parameter services of a node in another process, called from this one: what each
answers for known and unknown names, set vs set-atomically, and the events they cause."""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any

import pytest

from ros2lite.executors import SingleThreadedExecutor
from ros2lite.node import Node
from ros2lite.parameter import Parameter, parameter_value_to_python
from ros2lite.parameter_client import AsyncParameterClient

NODE_CODE = """
import sys
import ros2lite
from ros2lite.msgs.rcl_interfaces.msg import IntegerRange, ParameterDescriptor
from ros2lite.node import Node

with ros2lite.init(args=sys.argv):
    node = Node('served', namespace='/svc')
    node.declare_parameter('a.x', 1)
    node.declare_parameter('a.b.y', 'text')
    node.declare_parameter('limit', 3, ParameterDescriptor(
        integer_range=[IntegerRange(from_value=0, to_value=5, step=0)]))
    print('ready', flush=True)
    try:
        ros2lite.spin(node)
    except KeyboardInterrupt:
        pass
"""


class Remote:
    """The parameter client's calls, each waited for: `remote.get_parameters([...])` is the
    response."""

    def __init__(self, node: Node) -> None:
        self.node = node
        self.client = AsyncParameterClient(node, "/svc/served")
        self.executor = SingleThreadedExecutor(context=node.context)
        self.executor.add_node(node)

    def __getattr__(self, name: str) -> Any:
        def call(*args: Any, **kwargs: Any) -> Any:
            future = getattr(self.client, name)(*args, **kwargs)
            self.executor.spin_until_future_complete(future, 10.0)
            assert future.done(), name
            return future.result()

        return call


@pytest.fixture
def remote(ros_context: Any, processes: Any) -> Iterator[Remote]:
    proc = processes.python(NODE_CODE)
    assert proc.stdout.readline() == "ready\n"
    client_node = Node("_param_client", context=ros_context, start_parameter_services=False)
    remote = Remote(client_node)
    assert remote.client.wait_for_services(10.0)
    yield remote


def test_read_services(remote: Remote) -> None:
    values = remote.get_parameters(["a.x", "a.b.y"]).values
    assert [parameter_value_to_python(v) for v in values] == [1, "text"]
    assert remote.get_parameters(["a.x", "unknown"]).values == []
    assert list(remote.get_parameter_types(["a.x", "a.b.y", "use_sim_time"]).types) == [2, 4, 1]
    assert list(remote.get_parameter_types(["unknown"]).types) == []
    described = remote.describe_parameters(["limit"]).descriptors
    assert described[0].name == "limit" and described[0].integer_range[0].to_value == 5
    assert remote.describe_parameters(["limit", "unknown"]).descriptors == []
    everything = remote.list_parameters().result
    assert sorted(everything.names) == [
        "a.b.y",
        "a.x",
        "limit",
        "start_type_description_service",
        "use_sim_time",
    ]
    assert sorted(everything.prefixes) == ["a", "a.b"]
    assert remote.list_parameters(["a"], depth=1).result.names == ["a.x"]


def test_write_services(remote: Remote) -> None:
    results = remote.set_parameters(
        [Parameter("limit", value=4), Parameter("limit", value=9), Parameter("nope", value=1)]
    ).results
    assert [r.successful for r in results] == [True, False, False]
    assert results[1].reason == "Parameter limit out of range. Min: 0, Max: 5, value: 9"
    assert results[2].reason == "Invalid access to undeclared parameter(s): ['nope']"
    atomic = remote.set_parameters_atomically(
        [Parameter("a.x", value=7), Parameter("limit", value=9)]
    ).result
    assert not atomic.successful
    assert parameter_value_to_python(remote.get_parameters(["a.x"]).values[0]) == 1
    assert remote.set_parameters_atomically(
        [Parameter("a.x", value=7), Parameter("limit", value=0)]
    ).result.successful
    values = remote.get_parameters(["a.x", "limit"]).values
    assert [parameter_value_to_python(v) for v in values] == [7, 0]


def test_services_appear_in_the_graph(remote: Remote) -> None:
    services = dict(remote.node.get_service_names_and_types())
    for name in (
        "describe_parameters",
        "get_parameters",
        "get_parameter_types",
        "list_parameters",
        "set_parameters",
        "set_parameters_atomically",
    ):
        assert f"/svc/served/{name}" in services
