"""`param describe`: type, description and constraints as ros2cli prints them."""

from __future__ import annotations

from collections.abc import Callable

from tests.cli.conftest import Result


def test_describe(run: Callable[..., Result], target: str) -> None:
    result = run("param", "describe", target, "count", "fixed", "ratio", "name")
    assert (result.code, result.err) == (0, "")
    assert result.out == (
        "Parameter name: count\n  Type: integer\n  Description: How many\n  Constraints:\n"
        "    Min value: 0\n    Max value: 10\n    Step: 1\n"
        "Parameter name: fixed\n  Type: string\n  Constraints:\n    Read only: true\n"
        "    Additional constraints: never changes\n"
        "Parameter name: ratio\n  Type: double\n  Constraints:\n"
        "    Min value: 0.0\n    Max value: 2.0\n    Step: 0.5\n"
        "Parameter name: name\n  Type: string\n  Constraints:\n"
    )


def test_unknown_name_prints_nothing(run: Callable[..., Result], target: str) -> None:
    # rclpy empties the whole reply when one name is unknown; ros2cli then prints nothing
    assert run("param", "describe", target, "count", "nope").out == ""
