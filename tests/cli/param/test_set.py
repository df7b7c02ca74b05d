"""`param set` and `param delete`: YAML-typed values, several pairs, --atomic, and the
reasons a node gives (wrong type, read-only, range, static): a refusal is said on stderr and
exits 0, as ros2cli's."""

from __future__ import annotations

from collections.abc import Callable

from tests.cli.conftest import Result


def test_set_and_refusals(run: Callable[..., Result], fresh_target: str) -> None:
    node = fresh_target

    def get(name: str) -> str:
        return run("param", "get", node, name, "--hide-type").out.strip()

    ok = run("param", "set", node, "count", "7")
    assert (ok.code, ok.out, ok.err) == (0, "Set parameter successful\n", "")
    assert get("count") == "7"
    wrong = run("param", "set", node, "count", "seven")
    assert (wrong.code, wrong.out) == (0, "")
    assert wrong.err == (
        "Setting parameter failed: Wrong parameter type, expected "
        "'Type.INTEGER' got 'Type.STRING'\n"
    )
    assert (
        run("param", "set", node, "fixed", "x").err
        == "Setting parameter failed: Trying to set a read-only parameter: fixed.\n"
    )
    assert run("param", "set", node, "count", "11").err == (
        "Setting parameter failed: Parameter count out of range. Min: 0, Max: 10, value: 11\n"
    )
    assert run("param", "set", node, "names", "[x, y, z]").code == 0
    assert get("names") == "['x', 'y', 'z']"
    assert run("param", "set", node, "undeclared", "1").err.startswith(
        "Setting parameter failed: Invalid access to undeclared parameter(s): ['undeclared']"
    )
    # several pairs: one line each, prefixed with the name
    several = run("param", "set", node, "flag", "false", "ratio", "x")
    assert several.code == 0 and several.out == "flag: Set parameter successful\n"
    assert several.err.startswith("ratio: Setting parameter failed: Wrong parameter type")
    assert get("flag") == "False"
    # atomic: all or nothing
    failed = run("param", "set", node, "--atomic", "count", "3", "ratio", "x")
    assert failed.code == 0 and failed.err.startswith(
        "Setting parameters atomically failed: Wrong parameter type"
    )
    assert get("count") == "7"
    done = run("param", "set", node, "--atomic", "count", "3", "ratio", "0.5")
    assert done.out == "Set parameters atomically successful\n"
    assert (get("count"), get("ratio")) == ("3", "0.5")
    odd = run("param", "set", node, "count")
    assert odd.code == 1 and odd.err.startswith("Parameters must be provided as name/value")


def test_delete(run: Callable[..., Result], fresh_target: str) -> None:
    node = fresh_target
    static = run("param", "delete", node, "count")
    assert (static.code, static.err) == (
        0,
        "Deleting parameter failed: Static parameter cannot be undeclared\n",
    )
    assert (
        run("param", "delete", node, "fixed").err
        == "Deleting parameter failed: Trying to set a read-only parameter: fixed.\n"
    )
    result = run("param", "delete", node, "loose")
    assert (result.code, result.out) == (0, "Deleted parameter successfully\n")
    assert "loose" not in run("param", "list", node).out


def test_parameter_names_complete_where_a_name_goes(target: str) -> None:
    """`param set NODE <TAB>` offers the live node's parameters; after a name comes its value
    (nothing offered), then names again, less those already set on the line."""
    from tests.cli.test_completion import complete

    assert complete(f"ros2lite param set {target} na") == ["name", "names"]
    assert complete(f"ros2lite param set {target} name ") == []
    assert complete(f"ros2lite param set {target} name x na") == ["names"]
    every = "bools count doubles fixed flag ints loose name names nested.deep.value ratio"
    every += " start_type_description_service use_sim_time"
    assert complete(f"ros2lite param set {target} ") == every.split()
    assert complete("ros2lite param set /cli/no_such_node na") == []
