"""`draw_square` against a real turtlesim: it resets the world, then drives the first side
and the first corner of its 2 m square, logging its goals."""

from __future__ import annotations

import re
from collections.abc import Callable
from typing import Any

from tests.bundled.turtlesim.conftest import log_line, wait_for_log
from tests.bundled.turtlesim.test_node import pose
from tests.cli.conftest import Result


def test_first_side_and_corner(run: Callable[..., Result], turtlesim: Any, processes: Any) -> None:
    sim_proc, sim_lines = turtlesim
    # moved away first: the reset it starts with brings turtle1 back to the centre
    run('service', 'call', '/turtle1/teleport_absolute', 'turtlesim/srv/TeleportAbsolute',
        '{x: 1.0, y: 1.0, theta: 0.5}')  # fmt: skip
    proc = processes.cli('run', 'turtlesim', 'draw_square')
    lines: list[str] = []
    first = wait_for_log(proc, lines, r'New goal')
    assert re.fullmatch(
        log_line('draw_square', re.escape('New goal [7.544445 5.544445, 0.000000]')), first.strip()
    ), first
    wait_for_log(sim_proc, sim_lines, r'Resetting turtlesim\.$')
    wait_for_log(proc, lines, r'Reached goal')
    corner = wait_for_log(proc, lines, r'New goal', timeout=30, start=len(lines))
    x, y, theta = map(float, re.search(r'New goal \[(\S+) (\S+), (\S+)\]', corner).groups())  # type: ignore[union-attr]
    assert abs(x - 7.544445) < 0.1 and abs(y - 5.544445) < 0.01 and abs(theta - 1.570796) < 0.01
    p = pose(run)
    assert abs(p['x'] - 7.544445) < 0.1 and abs(p['y'] - 5.544445) < 0.01
    wait_for_log(proc, lines, r'Reached goal', timeout=30, start=len(lines))  # corner turned
    assert abs(pose(run)['theta'] - 1.570796) < 0.02
    processes.stop(proc)
    assert proc.returncode == 0
