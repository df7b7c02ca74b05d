"""Parameters on a real node: overrides from `--ros-args` (-p, params files with `/**`, `/*`
and namespaced names), the undeclared policy, automatic declaration, use_sim_time, and the
change events published on /parameter_events."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

from ros2lite.exceptions import InvalidParameterTypeException, ParameterNotDeclaredException
from ros2lite.interfaces import get_interface
from ros2lite.node import Node
from ros2lite.parameter import Parameter
from ros2lite.qos import qos_profile_parameter_events
from ros2lite.runtime.arguments import RosArgsError
from tests.spinning import spin_until

ParameterEvent = get_interface("rcl_interfaces/msg/ParameterEvent")


def test_overrides_from_files_and_command_line(ros_context: Any, tmp_path: Path) -> None:
    params = tmp_path / "params.yaml"
    params.write_text(
        "/**:\n  ros__parameters:\n    everyone: 1\n    rate: 1.0\n"
        "robot1:\n  driver:\n    ros__parameters:\n      rate: 2.0\n      pid: {p: 0.5}\n"
        "/robot1/*:\n  ros__parameters:\n    one_level: true\n"
        "/other:\n  ros__parameters:\n    everyone: 99\n"
    )
    args = [
        "--ros-args",
        "--params-file",
        str(params),
        "-p",
        "driver:label:=left",
        "-p",
        "listener:label:=nope",
    ]
    node = Node("driver", namespace="/robot1", context=ros_context, cli_args=args)
    assert node.declare_parameter("everyone", 0).value == 1
    assert node.declare_parameter("rate", 0.0).value == 2.0
    assert node.declare_parameter("pid.p", 0.0).value == 0.5
    assert node.declare_parameter("one_level", False).value is True
    assert node.declare_parameter("label", "").value == "left"
    deeper = Node("driver", namespace="/robot1/arm", context=ros_context, cli_args=args)
    # '/*' is exactly one segment: /robot1/arm/driver is not under it
    assert deeper.declare_parameter("one_level", False).value is False
    assert deeper.declare_parameter("rate", 0.0).value == 1.0


def test_an_override_of_another_type_is_refused(ros_context: Any) -> None:
    node = Node("typed", context=ros_context, cli_args=["--ros-args", "-p", "rate:=5"])
    with pytest.raises(InvalidParameterTypeException, match="expecting type 'DOUBLE'"):
        node.declare_parameter("rate", 1.0)
    with pytest.raises(RosArgsError, match="Invalid value for parameter override 'mixed'"):
        Node("bad", context=ros_context, cli_args=["--ros-args", "-p", "mixed:=[1, a]"])


def test_automatic_declaration_and_undeclared_policy(ros_context: Any) -> None:
    node = Node(
        "board",
        context=ros_context,
        cli_args=["--ros-args", "-p", "x:=3", "-p", "names:=[a, b]"],
        parameter_overrides=[Parameter("from_code", value=2.5)],
        automatically_declare_parameters_from_overrides=True,
    )
    assert sorted(node.list_parameters([], 0).names) == [
        "from_code",
        "names",
        "start_type_description_service",
        "use_sim_time",
        "x",
    ]
    assert node.get_parameter("names").value == ["a", "b"]
    with pytest.raises(ParameterNotDeclaredException):
        node.set_parameters([Parameter("fresh", value=1)])
    loose = Node("loose", context=ros_context, allow_undeclared_parameters=True)
    assert loose.set_parameters([Parameter("fresh", value=1)])[0].successful
    assert loose.get_parameter("fresh").value == 1


def test_use_sim_time_is_a_checked_parameter(ros_context: Any) -> None:
    node = Node("clocked", context=ros_context)
    assert node.get_parameter("use_sim_time").value is False
    assert not node.get_clock().ros_time_is_active
    assert node.set_parameters([Parameter("use_sim_time", value=True)])[0].successful
    assert node.get_clock().ros_time_is_active
    # declared from an override, it is typed by the override's value
    auto = Node(
        "auto_clock",
        context=ros_context,
        cli_args=["--ros-args", "-p", "use_sim_time:=true"],
        automatically_declare_parameters_from_overrides=True,
    )
    assert auto.get_clock().ros_time_is_active
    outcome = auto.set_parameters([Parameter("use_sim_time", value="yes")])[0]
    assert (outcome.successful, outcome.reason) == (
        False,
        "Wrong parameter type, expected 'Type.BOOL' got 'Type.STRING'",
    )
    # undeclared and set again dynamically, it still only takes booleans
    loose = Node("loose_clock", context=ros_context, allow_undeclared_parameters=True)
    loose.undeclare_parameter("use_sim_time")
    outcome = loose.set_parameters([Parameter("use_sim_time", value="yes")])[0]
    assert (outcome.successful, outcome.reason) == (
        False,
        "use_sim_time parameter set to something besides a bool",
    )
    assert loose.set_parameters([Parameter("use_sim_time", value=True)])[0].successful
    assert loose.get_clock().ros_time_is_active
    assert auto.get_clock().ros_time_is_active


def test_parameter_events(ros_context: Any) -> None:
    from ros2lite.executors import SingleThreadedExecutor

    listener = Node("event_listener", context=ros_context)
    events: list[Any] = []
    listener.create_subscription(
        ParameterEvent,
        "/parameter_events",
        lambda e: events.append(e) if e.node == "/ns/talker" else None,
        qos_profile_parameter_events,
    )
    ex = SingleThreadedExecutor(context=ros_context)
    ex.add_node(listener)
    node = Node("talker", namespace="/ns", context=ros_context, allow_undeclared_parameters=True)
    # its own use_sim_time declaration may precede discovery; wait until events flow
    spin_until(
        ex, lambda: node.set_parameters([Parameter("probe", value=0)]) and events, timeout=10
    )
    events.clear()
    node.declare_parameter("gain", 1.5)
    node.set_parameters([Parameter("gain", value=2.5)])
    node.set_parameters_atomically([Parameter("probe"), Parameter("gain", value=3.5)])
    node.undeclare_parameter("gain")
    gain_events: list[Any] = []

    def four_about_gain() -> bool:
        # probe sets still in flight may arrive late: look at the events about 'gain'
        gain_events[:] = [
            e
            for e in events
            if any(
                m.name == "gain"
                for m in [*e.new_parameters, *e.changed_parameters, *e.deleted_parameters]
            )
        ]
        return len(gain_events) >= 4

    spin_until(ex, four_about_gain)

    def names(msgs: list[Any]) -> list[tuple[str, Any]]:
        return [(m.name, Parameter.from_parameter_msg(m).value) for m in msgs]

    summary = [
        (names(e.new_parameters), names(e.changed_parameters), names(e.deleted_parameters))
        for e in gain_events
    ]
    assert summary == [
        ([("gain", 1.5)], [], []),
        ([], [("gain", 2.5)], []),
        ([], [("gain", 3.5)], [("probe", None)]),
        ([], [], [("gain", None)]),
    ]
    assert all(e.stamp.sec > 0 for e in gain_events)
