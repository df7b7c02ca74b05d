"""`ROS_DISTRO=kilted`: turtlesim serves Kilted's names, the `turtlesim_msgs` interfaces
(Jazzy's node serves the `turtlesim` package's)."""

from __future__ import annotations

import os
from typing import Any

from tests.bundled.turtlesim.conftest import wait_for_log


def test_kilted_turtlesim_answers_a_turtlesim_msgs_spawn(processes: Any, run: Any) -> None:
    proc = processes.cli(
        'run', 'turtlesim', 'turtlesim_node', '--display', 'none',
        env={**os.environ, 'ROS_DISTRO': 'kilted'},
    )  # fmt: skip
    lines: list[str] = []
    wait_for_log(proc, lines, r'Spawning turtle \[turtle1\]')
    assert run('service', 'type', '/spawn').out == 'turtlesim_msgs/srv/Spawn\n'
    assert run('topic', 'type', '/turtle1/pose').out == 'turtlesim_msgs/msg/Pose\n'
    out = run('service', 'call', '/spawn', 'turtlesim_msgs/srv/Spawn', '{x: 2, y: 2}').out
    assert "turtlesim_msgs.srv.Spawn_Response(name='turtle2')" in out
    wait_for_log(proc, lines, r'Spawning turtle \[turtle2\] at x=\[2\.0+\]')
    _out, err = processes.stop(proc)
    assert proc.returncode == 0, err
