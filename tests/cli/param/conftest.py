"""A node with parameters of every kind, running in its own process for the whole module."""

from __future__ import annotations

import subprocess
import sys
from collections.abc import Iterator

import pytest

TARGET = "/cli/param_target"

# declares one parameter per kind, plus a range, a read-only one and a nested name
TARGET_CODE = """
import sys
import ros2lite
from ros2lite.msgs.rcl_interfaces.msg import IntegerRange, FloatingPointRange, ParameterDescriptor
from ros2lite.node import Node

with ros2lite.init(args=sys.argv):
    node = Node(sys.argv[1], namespace='/cli')
    node.declare_parameter('flag', True)
    node.declare_parameter('count', 5, ParameterDescriptor(
        description='How many', integer_range=[IntegerRange(from_value=0, to_value=10, step=1)]))
    node.declare_parameter('ratio', 1.5, ParameterDescriptor(floating_point_range=[
        FloatingPointRange(from_value=0.0, to_value=2.0, step=0.5)]))
    node.declare_parameter('name', 'foo')
    node.declare_parameter('names', ['a', 'b'])
    node.declare_parameter('ints', [1, 2])
    node.declare_parameter('bools', [True, False])
    node.declare_parameter('doubles', [0.5, 2.0])
    node.declare_parameter('fixed', 'const', ParameterDescriptor(
        read_only=True, additional_constraints='never changes'))
    node.declare_parameter('nested.deep.value', 3)
    node.declare_parameter('loose', 1, ParameterDescriptor(dynamic_typing=True))
    print('ready', flush=True)
    try:
        ros2lite.spin(node)
    except KeyboardInterrupt:
        pass
"""


def start_target(name: str) -> subprocess.Popen[str]:
    proc = subprocess.Popen(
        [sys.executable, "-c", TARGET_CODE, name],
        text=True,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
    )
    assert proc.stdout is not None
    line = proc.stdout.readline()
    assert line == "ready\n", proc.stderr.read() if proc.stderr else line
    return proc


def stop(proc: subprocess.Popen[str]) -> None:
    proc.terminate()
    try:
        proc.communicate(timeout=10)
    except subprocess.TimeoutExpired:
        proc.kill()
        proc.communicate()


@pytest.fixture(scope="package")
def target(ros_router: str) -> Iterator[str]:
    """`/cli/param_target`, shared by every test here: only read it."""
    proc = start_target("param_target")
    try:
        yield TARGET
    finally:
        stop(proc)


@pytest.fixture
def fresh_target(ros_router: str) -> Iterator[str]:
    """`/cli/param_scratch`, the same parameters, for one test that changes them."""
    proc = start_target("param_scratch")
    try:
        yield "/cli/param_scratch"
    finally:
        stop(proc)
