"""`param list`: one node, every node, types, prefixes, a regex filter, hidden nodes."""

from __future__ import annotations

from collections.abc import Callable

from tests.cli.conftest import Result

NAMES = [
    "bools",
    "count",
    "doubles",
    "fixed",
    "flag",
    "ints",
    "loose",
    "name",
    "names",
    "nested.deep.value",
    "ratio",
    "start_type_description_service",
    "use_sim_time",
]


def test_one_node(run: Callable[..., Result], target: str) -> None:
    result = run("param", "list", target)
    assert (result.code, result.err) == (0, "")
    assert result.out == "".join(f"  {n}\n" for n in NAMES)


def test_every_node_has_a_header(run: Callable[..., Result], target: str) -> None:
    out = run("param", "list").out
    lines = out.splitlines()
    start = lines.index(f"{target}:")
    assert lines[start + 1 : start + 1 + len(NAMES)] == [f"  {n}" for n in NAMES]
    headers = [line[:-1] for line in lines if not line.startswith(" ")]
    assert headers == sorted(headers)


def test_types_prefixes_and_filter(run: Callable[..., Result], target: str) -> None:
    typed = run("param", "list", target, "--param-type").out.splitlines()
    assert "  count (type: integer)" in typed and "  names (type: string array)" in typed
    assert "  use_sim_time (type: boolean)" in typed
    assert run("param", "list", target, "--param-prefixes", "nested").out == "  nested.deep.value\n"
    # several prefixes after one flag, as argparse's nargs='+' takes them, before the node
    assert (
        run("param", "list", "--param-prefixes", "nested", "use_sim_time", "--", target).out
        == "  nested.deep.value\n  use_sim_time\n"
    )
    assert (
        run("param", "list", target, "--param-prefixes", "nested", "--param-prefixes", "fixed").out
        == "  fixed\n  nested.deep.value\n"
    )
    assert run("param", "list", target, "--filter", "n.*s$").out == "  names\n"
    bad = run("param", "list", target, "--filter", "(")
    assert bad.code == 1 and bad.err.startswith("Invalid regular expression '('")


def test_unknown_and_hidden_nodes(
    run: Callable[..., Result], target: str, ros_context: object
) -> None:
    from ros2lite.node import Node

    Node("_hidden_params", context=ros_context)
    result = run("param", "list", "/no_such_node")
    assert (result.code, result.err) == (1, "Node not found\n")
    assert run("param", "list", "/_hidden_params").err == "Node not found\n"
    assert "/_hidden_params:" not in run("param", "list").out
