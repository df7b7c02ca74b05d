"""ROS names: rcl's validation rules, expansion, hidden names and rclpy's exceptions."""

from __future__ import annotations

import pytest

from ros2lite import names
from ros2lite.exceptions import (
    InvalidNamespaceException,
    InvalidNodeNameException,
    InvalidServiceNameException,
    InvalidTopicNameException,
)


@pytest.mark.parametrize(
    "name", ["chatter", "/chatter", "~", "~/foo", "a/b_c/D9", "{node}/x", "/ns/{ns}", "_hidden"]
)
def test_valid_topic_names(name: str) -> None:
    names.validate_topic_name(name)


@pytest.mark.parametrize(
    ("name", "why"),
    [
        ("", "empty"),
        ("/foo/", "end with '/'"),
        ("foo//bar", "repeated '/'"),
        ("9foo", "must not start with a number"),
        ("/foo/9bar", "must not start with a number"),
        ("foo bar", "must not contain characters other than"),
        ("foo-bar", "must not contain characters other than"),
        ("a/~", "'~'"),
        ("~foo", "'~'"),
        ("{a", "unbalanced"),
        ("a}", "unbalanced"),
        ("{a-b}", "must not contain characters other than"),
        ("{}", "substitution"),
    ],
)
def test_invalid_topic_names(name: str, why: str) -> None:
    with pytest.raises(ValueError, match=r"topic name.* is invalid") as err:
        names.validate_topic_name(name)
    assert why in str(err.value)


def test_full_names_nodes_namespaces() -> None:
    names.validate_full_topic_name("/a/b")
    for bad in ("a/b", "/a/", "/a//b", "/~", "/1a"):
        with pytest.raises(ValueError):
            names.validate_full_topic_name(bad)
    names.validate_node_name("talker_1")
    for bad in ("", "1talker", "tal/ker", "tal-ker"):
        with pytest.raises(ValueError, match="node name"):
            names.validate_node_name(bad)
    names.validate_namespace("/")
    names.validate_namespace("/a/b")
    for bad in ("", "a", "/a/", "/a//b", "/1a", "/a-b"):
        with pytest.raises(ValueError, match="namespace"):
            names.validate_namespace(bad)
    assert names.normalize_namespace(None) == "/"
    assert names.normalize_namespace("") == "/"
    assert names.normalize_namespace("robot1") == "/robot1"
    assert names.normalize_namespace("/robot1/") == "/robot1"


@pytest.mark.parametrize(
    ("name", "node", "ns", "expected"),
    [
        ("chatter", "talker", "/", "/chatter"),
        ("chatter", "talker", "/robot1", "/robot1/chatter"),
        ("/abs", "talker", "/robot1", "/abs"),
        ("~", "talker", "/ns", "/ns/talker"),
        ("~/foo", "talker", "/ns", "/ns/talker/foo"),
        ("~/foo", "talker", "/", "/talker/foo"),
        ("{node}/x", "talker", "/ns", "/ns/talker/x"),
        ("{ns}/x", "talker", "/ns", "/ns/x"),
        ("{namespace}/x", "talker", "/", "/x"),
    ],
)
def test_expand_topic_name(name: str, node: str, ns: str, expected: str) -> None:
    assert names.expand_topic_name(name, node, ns) == expected


def test_expand_rejects_bad_input() -> None:
    with pytest.raises(ValueError, match="unknown substitution"):
        names.expand_topic_name("{robot}/x", "talker", "/")
    with pytest.raises(ValueError, match="node name"):
        names.expand_topic_name("x", "9talker", "/")


def test_fqn_helpers() -> None:
    assert names.node_fqn("/", "n") == "/n"
    assert names.node_fqn("/a/b", "n") == "/a/b/n"
    assert names.split_fqn("/a/b/n") == ("/a/b", "n")
    assert names.split_fqn("/n") == ("/", "n")
    assert names.is_hidden_name("/_ros2cli_123")
    assert names.is_hidden_name("/a/_b/c")
    assert not names.is_hidden_name("/a/b_c")


def test_rclpy_exceptions_are_value_errors() -> None:
    """rclpy's names, and still ValueErrors for code that catches those."""
    with pytest.raises(InvalidTopicNameException):
        names.validate_topic_name('9x')
    with pytest.raises(InvalidServiceNameException, match=r"service name.* is invalid"):
        names.validate_topic_name('9x', is_service=True)
    with pytest.raises(InvalidServiceNameException, match=r"service name.* is invalid"):
        names.expand_topic_name('a b', 'n', '/', is_service=True)
    with pytest.raises(InvalidNodeNameException):
        names.validate_node_name('a-b')
    with pytest.raises(InvalidNamespaceException):
        names.validate_namespace('ns')
    with pytest.raises(ValueError):
        names.validate_full_topic_name('/a//b')
    assert names.absolute_node_name('talker') == '/talker'
    assert names.absolute_node_name('/ns/talker') == '/ns/talker'
