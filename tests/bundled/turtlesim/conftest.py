"""Shared by the turtlesim tests: the in-process CLI, and a running `turtlesim_node`."""

from __future__ import annotations

import re
import time
from collections.abc import Iterator
from typing import Any

import pytest

from tests.bundled.test_demo_nodes_py import log_line
from tests.cli.conftest import run  # noqa: F401  # the `run` fixture: the CLI in-process

__all__ = ['log_line', 'start_turtlesim', 'wait_for_log']


def wait_for_log(
    proc: Any, lines: list[str], pattern: str, timeout: float = 20.0, start: int = 0
) -> str:
    """Read the process's stderr into `lines` until a line (from index `start` on) matches
    `pattern`."""
    deadline = time.monotonic() + timeout
    regex = re.compile(pattern)
    for line in lines[start:]:
        if regex.search(line):
            return line
    while time.monotonic() < deadline:
        line = proc.stderr.readline()
        if not line:
            if proc.poll() is not None:
                break
            continue
        lines.append(line.rstrip('\n'))
        if regex.search(line):
            return line
    raise AssertionError(f'no line matching {pattern!r} in:\n' + '\n'.join(lines))


def start_turtlesim(processes: Any, *args: str) -> tuple[Any, list[str]]:
    """`ros2lite run turtlesim turtlesim_node ARGS`, once it has spawned turtle1."""
    proc = processes.cli('run', 'turtlesim', 'turtlesim_node', *args)
    lines: list[str] = []
    wait_for_log(proc, lines, r'Spawning turtle \[turtle1\]')
    return proc, lines


@pytest.fixture
def turtlesim(processes: Any) -> Iterator[tuple[Any, list[str]]]:
    """A headless turtlesim node for the test."""
    yield start_turtlesim(processes, '--display', 'none')
