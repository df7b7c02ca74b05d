"""`param dump` and `param load`: the YAML layout, --output-dir, and a round trip that brings
changed values back; wildcard entries and per-parameter reports."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

from tests.cli.conftest import Result

DUMP = """/cli/param_target:
  ros__parameters:
    bools:
    - true
    - false
    count: 5
    doubles:
    - 0.5
    - 2.0
    fixed: const
    flag: true
    ints:
    - 1
    - 2
    loose: 1
    name: foo
    names:
    - a
    - b
    nested:
      deep:
        value: 3
    ratio: 1.5
    start_type_description_service: true
    use_sim_time: false

"""


def test_dump(run: Callable[..., Result], target: str, tmp_path: Path) -> None:
    result = run("param", "dump", target)
    assert (result.code, result.out, result.err) == (0, DUMP, "")
    written = run("param", "dump", target, "--output-dir", str(tmp_path / "out"))
    assert (written.code, written.out) == (0, "")
    assert (tmp_path / "out" / "cli__param_target.yaml").read_text() == DUMP[:-1]


def test_round_trip(run: Callable[..., Result], fresh_target: str, tmp_path: Path) -> None:
    node = fresh_target
    saved = tmp_path / "saved.yaml"
    saved.write_text(run("param", "dump", node).out)
    assert run("param", "set", node, "count", "9", "names", "[z]", "name", "'5'").code == 0
    result = run("param", "load", node, str(saved))
    assert result.code == 0
    assert "Set parameter count successful\n" in result.out
    # read-only and unchanged-type failures are reported, the rest goes through (the node's
    # own read-only start_type_description_service too, as with rclpy nodes)
    assert result.err == (
        "Set parameter fixed failed: Trying to set a read-only parameter: fixed.\n"
        "Set parameter start_type_description_service failed: Trying to set a read-only "
        "parameter: start_type_description_service.\n"
    )
    assert run("param", "dump", node).out == saved.read_text().replace("/cli/param_target", node)
    # a string that looks like a number stays a string through dump and load
    run("param", "set", node, "name", "'5'")
    saved.write_text(run("param", "dump", node).out)
    run("param", "set", node, "name", "other")
    run("param", "load", node, str(saved))
    assert run("param", "get", node, "name").out == "String value is: 5\n"


def test_load_wildcards_and_errors(
    run: Callable[..., Result], fresh_target: str, tmp_path: Path
) -> None:
    node = fresh_target
    path = tmp_path / "p.yaml"
    path.write_text(
        "/**:\n  ros__parameters:\n    count: 1\n    name: everyone\n"
        "cli:\n  param_scratch:\n    ros__parameters:\n      name: mine\n"
    )
    result = run("param", "load", node, str(path))
    assert result.out == "Set parameter count successful\nSet parameter name successful\n"
    assert run("param", "get", node, "name", "--hide-type").out == "mine\n"
    result = run("param", "load", node, str(path), "--no-use-wildcard")
    assert result.out == "Set parameter name successful\n"
    only_wild = tmp_path / "w.yaml"
    only_wild.write_text("/**:\n  ros__parameters:\n    count: 2\n")
    refused = run("param", "load", node, str(only_wild), "--no-use-wildcard")
    assert refused.code == 1
    assert refused.err.startswith("Param file does not contain parameters for /cli/param_scratch")
    missing = run("param", "load", node, str(tmp_path / "absent.yaml"))
    assert missing.code == 1 and "No such file or directory" in missing.err
