"""The simulator's pictures as a person sees them: `turtlebot3_world.launch.py` with a display
opens the top view window (Gazebo's client, `gui:=true` by default), showing the robot and
its laser's hits on the world's walls and pillars under Xvfb, and the terminal view
(`python -m ros2lite.bundled.rviz2.top_view`) shows the same in tmux. One launch serves
both. (`gui:=false` opening none: tests/bundled/turtlebot3_gazebo/test_turtlebot3_gazebo.py.)"""

from __future__ import annotations

import os
import subprocess
import sys
import threading
from collections.abc import Iterator
from contextlib import ExitStack
from pathlib import Path
from typing import Any

import pytest

from ros2lite.bundled.rviz2.top_view import ROBOT, SCAN
from tests.bundled.conftest import xvfb, xvfb_missing
from tests.bundled.rviz2.test_top_view import cells, colour_box, where
from tests.bundled.screenshot import Image, screenshot
from tests.bundled.tmux import TmuxPane
from tests.spinning import wait_until


@pytest.fixture(scope='module')
def world(ros_router: str) -> Iterator[str]:
    """turtlebot3_world.launch.py with a virtual display when there can be one; the display
    (or '' without Xvfb)."""
    from tests.conftest import Processes

    procs = Processes()
    with ExitStack() as stack:
        display = '' if xvfb_missing() else stack.enter_context(xvfb())
        env = {k: v for k, v in os.environ.items() if k not in ('DISPLAY', 'WAYLAND_DISPLAY')}
        if display:
            env['DISPLAY'] = display
        proc = procs.cli(
            'launch', 'turtlebot3_gazebo', 'turtlebot3_world.launch.py',
            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, env=env,
        )  # fmt: skip
        lines: list[str] = []

        def read() -> None:
            assert proc.stdout is not None
            for line in proc.stdout:
                lines.append(line)

        threading.Thread(target=read, daemon=True).start()
        try:
            wait_until(lambda: any('2D stand-in' in line for line in lines), timeout=30)
            yield display
        finally:
            procs.close()


@pytest.mark.timeout(90)
def test_the_launch_line_opens_the_window(world: str, tmp_path: Path) -> None:
    if not world:
        pytest.skip(xvfb_missing())
    xdisplay = world

    def ready() -> Image | None:
        img = screenshot(xdisplay)
        robot, hits = len(colour_box(img, ROBOT)), len(colour_box(img, SCAN))
        return img if robot > 20 and hits > 150 else None

    img = wait_until(ready, 45)
    img.save_png(str(tmp_path / 'turtlebot3_world.png'))
    robot = colour_box(img, ROBOT)
    hits = colour_box(img, SCAN)
    # the burger at its spawn point (-2, -0.5) of the world's hexagon, the hits around it
    # on every side: the pillars and the walls
    rx = sum(x for x, _ in robot) / len(robot)
    ry = sum(y for _, y in robot) / len(robot)
    assert min(x for x, _ in hits) < rx < max(x for x, _ in hits)
    assert min(y for _, y in hits) < ry < max(y for _, y in hits)


@pytest.mark.timeout(90)
def test_the_terminal_view_shows_the_same(world: str, tmp_path: Path) -> None:
    plain = {k: v for k, v in os.environ.items() if k not in ('DISPLAY', 'WAYLAND_DISPLAY')}
    pane = TmuxPane(
        [sys.executable, '-m', 'ros2lite.bundled.rviz2.top_view', '--no-frames'],
        plain,
        tmp_path,
        cols=100,
        rows=32,
    )
    try:

        def shown() -> list[list[Any]] | None:
            grid = cells(pane.screen(colours=True))
            return grid if len(where(grid, SCAN)) > 40 and where(grid, ROBOT) else None

        grid = wait_until(shown, 45)
        hits, robot = where(grid, SCAN), where(grid, ROBOT)
        rc = sum(c for c, _ in robot) / len(robot)
        rr = sum(r for _, r in robot) / len(robot)
        assert min(c for c, _ in hits) < rc < max(c for c, _ in hits)
        assert min(r for _, r in hits) < rr < max(r for _, r in hits)
        (tmp_path / 'pane.txt').write_text(pane.screen())
    finally:
        pane.close()
