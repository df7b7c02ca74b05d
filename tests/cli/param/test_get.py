"""`param get`: every type's label and value, --hide-type, unknown parameter and node."""

from __future__ import annotations

from collections.abc import Callable

import pytest

from tests.cli.conftest import Result


@pytest.mark.parametrize(
    "name, line",
    [
        ("flag", "Boolean value is: True"),
        ("count", "Integer value is: 5"),
        ("ratio", "Double value is: 1.5"),
        ("name", "String value is: foo"),
        ("names", "String values are: ['a', 'b']"),
        ("ints", "Integer values are: [1, 2]"),
        ("bools", "Boolean values are: [True, False]"),
        ("doubles", "Double values are: [0.5, 2.0]"),
        ("nested.deep.value", "Integer value is: 3"),
    ],
)
def test_values_and_labels(run: Callable[..., Result], target: str, name: str, line: str) -> None:
    result = run("param", "get", target, name)
    assert (result.code, result.out, result.err) == (0, line + "\n", "")


def test_hide_type_and_relative_node_name(run: Callable[..., Result], target: str) -> None:
    assert run("param", "get", target.lstrip("/"), "ints", "--hide-type").out == "[1, 2]\n"


def test_unknown_parameter_and_node(run: Callable[..., Result], target: str) -> None:
    result = run("param", "get", target, "nope")
    assert (result.code, result.out, result.err) == (1, "", "Parameter not set\n")
    result = run("param", "get", "/cli/no_such_node", "x", "--timeout", "0")
    assert (result.code, result.out, result.err) == (1, "", "Node not found\n")


def test_node_without_parameter_services(
    run: Callable[..., Result], ros_context: object, monkeypatch: pytest.MonkeyPatch
) -> None:
    from ros2lite.node import Node

    Node("no_param_services", context=ros_context, start_parameter_services=False)
    monkeypatch.setattr("ros2lite.cli.param.common.SERVICE_WAIT", 0.3)  # ros2cli waits 5 s
    result = run("param", "get", "/no_param_services", "x")
    assert (result.code, result.out) == (1, "")
    assert result.err == (
        "Wait for service timed out waiting for parameter services for node /no_param_services\n"
    )


def test_parameter_names_complete_from_the_node(target: str) -> None:
    from tests.cli.test_completion import complete

    assert complete(f"ros2lite param get {target} na") == ["name", "names"]
    assert complete(f"ros2lite param describe {target} count nes") == ["nested.deep.value"]
    assert complete("ros2lite param get /cli/no_such_node na") == []
