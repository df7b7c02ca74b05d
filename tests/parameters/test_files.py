"""Parameter files: rcl's node-name matching (`/*`, `/**`, nested namespaces), flattening,
errors, and the `param dump` layout read back the same."""

from __future__ import annotations

from pathlib import Path

import pytest
import yaml

from ros2lite.parameters.files import (
    ParamsFileError,
    dump_file_name,
    dump_yaml,
    matches,
    read_params_file,
    values_for_node,
)


@pytest.mark.parametrize(
    "pattern, fqn, expected",
    [
        ("/**", "/a", True),
        ("/**", "/ns/deep/a", True),
        ("/*", "/a", True),
        ("/*", "/ns/a", False),
        ("/ns/*", "/ns/a", True),
        ("/ns/*", "/ns/x/a", False),
        ("/**/a", "/a", True),
        ("/**/a", "/x/y/a", True),
        ("/**/a", "/x/b", False),
        ("talker", "/talker", True),
        ("talker", "/ns/talker", False),
        ("/ns/talker", "/ns/talker", True),
        ("/a.b", "/aXb", False),
    ],
)
def test_node_name_matching(pattern: str, fqn: str, expected: bool) -> None:
    assert matches(pattern, fqn) is expected


def test_entries_nesting_and_order(tmp_path: Path) -> None:
    path = tmp_path / "p.yaml"
    path.write_text(
        "/**:\n  ros__parameters:\n    shared: all\n    deep: {a: {b: 1}}\n"
        "robot1:\n  talker:\n    ros__parameters:\n      shared: nested-ns\n"
        "/robot1/*:\n  ros__parameters:\n    one_level: true\n"
    )
    assert read_params_file(path) == [
        ("/**", {"shared": "all", "deep.a.b": 1}),
        ("/robot1/talker", {"shared": "nested-ns"}),
        ("/robot1/*", {"one_level": True}),
    ]
    assert values_for_node(path, "/robot1/talker") == {
        "shared": "nested-ns",
        "deep.a.b": 1,
        "one_level": True,
    }
    assert values_for_node(path, "/other") == {"shared": "all", "deep.a.b": 1}
    assert values_for_node(path, "/robot1/talker", use_wildcard=False) == {"shared": "nested-ns"}


@pytest.mark.parametrize(
    "text, message",
    [
        ("- a\n", "must map node names"),
        ("n:\n  ros__parameters: 3\n", "ros__parameters"),
        ("n: 3\n", "ros__parameters"),
        ("a: [unclosed\n", "Couldn't read"),
    ],
)
def test_errors(tmp_path: Path, text: str, message: str) -> None:
    path = tmp_path / "bad.yaml"
    path.write_text(text)
    with pytest.raises(ParamsFileError, match=message):
        read_params_file(path)


def test_missing_file(tmp_path: Path) -> None:
    with pytest.raises(ParamsFileError, match="Couldn't read"):
        read_params_file(tmp_path / "absent.yaml")


def test_dump_layout_and_round_trip(tmp_path: Path) -> None:
    values = {"use_sim_time": False, "b.x": 1, "b.y": [1.5, 2.0], "a": "text", "b.z.w": ["s"]}
    text = dump_yaml("/ns/node", values)
    assert text == (
        "/ns/node:\n  ros__parameters:\n    a: text\n    b:\n      x: 1\n"
        "      y:\n      - 1.5\n      - 2.0\n      z:\n        w:\n        - s\n"
        "    use_sim_time: false\n"
    )
    path = tmp_path / dump_file_name("/ns/node")
    assert path.name == "ns__node.yaml"
    path.write_text(text)
    assert values_for_node(path, "/ns/node") == values
    assert yaml.safe_load(text)["/ns/node"]["ros__parameters"]["b"]["x"] == 1


def test_dump_keeps_clashing_names_flat() -> None:
    tree = yaml.safe_load(dump_yaml("/n", {"a": 1, "a.b": 2}))
    assert tree == {"/n": {"ros__parameters": {"a": 1, "a.b": 2}}}


def test_repeated_node_keys_keep_every_entry(tmp_path: Path) -> None:
    """rcl reads the file as a stream: a node key written twice contributes both entries
    (PyYAML alone would keep only the last)."""
    path = tmp_path / "twice.yaml"
    path.write_text(
        "/**:\n  ros__parameters:\n    a: 1\n"
        "/n:\n  ros__parameters:\n    b: 2\n"
        "/**:\n  ros__parameters:\n    c: 3\n"
        "ns:\n  n2:\n    ros__parameters:\n      d: 4\n"
        "ns:\n  n2:\n    ros__parameters:\n      e: 5\n"
    )
    assert values_for_node(path, "/n") == {"a": 1, "b": 2, "c": 3}
    assert values_for_node(path, "/ns/n2") == {"a": 1, "c": 3, "d": 4, "e": 5}


def test_parameter_dict_from_yaml_file(tmp_path: Path) -> None:
    from ros2lite.parameters.files import parameter_dict_from_yaml_file

    path = tmp_path / "p.yaml"
    path.write_text(
        "/**:\n  ros__parameters:\n    shared: 0\n"
        "/x:\n  ros__parameters:\n    one: 1\n    shared: 10\n"
        "/y:\n  ros__parameters:\n    two: [a, b]\n"
    )
    every = parameter_dict_from_yaml_file(path)  # every node's entries, not the wildcard
    assert sorted(every) == ["one", "shared", "two"] and every["shared"].value.integer_value == 10
    wild = parameter_dict_from_yaml_file(path, use_wildcard=True, target_nodes=["y"])
    assert sorted(wild) == ["shared", "two"] and wild["shared"].value.integer_value == 0
    assert list(parameter_dict_from_yaml_file(path, target_nodes=["/x"], namespace="ns")) == [
        "ns.one",
        "ns.shared",
    ]
    with pytest.raises(RuntimeError, match="does not contain parameters for /z"):
        parameter_dict_from_yaml_file(path, target_nodes=["/z"])
    with pytest.raises(FileNotFoundError):
        parameter_dict_from_yaml_file(tmp_path / "absent.yaml")
