"""The scene from above against real nodes — a static map -> odom, a broadcaster of odom ->
base_link and the LaserScan of a 4 m square room — as a person sees it: in tmux (the hits on
the room's four walls, the robot's outline where it stands, a hostile frame name escaped, keys
that zoom and quit) and in a window under a virtual X display (the hits' and the robot's
pixels)."""

from __future__ import annotations

import os
import re
import sys
from pathlib import Path
from typing import Any

from ros2lite.bundled.rviz2.top_view import ROBOT, SCAN
from ros2lite.bundled.rviz2.top_window import BACKGROUND
from tests.bundled.screenshot import Image, screenshot
from tests.bundled.tmux import TmuxPane
from tests.spinning import wait_until

ROOM = str(Path(__file__).with_name('room.py'))
X, Y, YAW = 1.0, 0.5, 0.3  # where the robot stands in the room (walls at +-2 m)
HOSTILE = 'evil\x1b]2;pwned\x07frame'
_SGR = re.compile(r'\x1b\[([0-9;]*)m')


def start_world(processes: Any) -> None:
    """The three publishers, as real node processes."""
    processes.cli(
        'run', 'tf2_ros', 'static_transform_publisher', '--frame-id', 'map',
        '--child-frame-id', 'odom',
    )  # fmt: skip
    processes.cli(
        'run', 'tf2_ros', 'static_transform_publisher', '--x', '-1.5', '--y', '-1.5',
        '--frame-id', 'map', '--child-frame-id', HOSTILE,
    )  # fmt: skip
    processes.start([sys.executable, ROOM, str(X), str(Y), str(YAW), '20'])


def cells(screen: str) -> list[list[tuple[str, tuple[int, int, int] | None]]]:
    """The pane's characters with their foreground colours (from capture-pane -e)."""
    rows = []
    for line in screen.split('\n'):
        row: list[tuple[str, tuple[int, int, int] | None]] = []
        fg: tuple[int, int, int] | None = None
        pos = 0
        for m in _SGR.finditer(line):
            row.extend((ch, fg) for ch in line[pos : m.start()])
            pos = m.end()
            params = [int(p) if p else 0 for p in m.group(1).split(';')]
            k = 0
            while k < len(params):
                p = params[k]
                if p in (0, 39):
                    fg = None
                if p == 38 and params[k + 1 : k + 2] == [2]:
                    fg = (params[k + 2], params[k + 3], params[k + 4])
                    k += 4
                elif p == 48 and params[k + 1 : k + 2] == [2]:
                    k += 4
                k += 1
        row.extend((ch, fg) for ch in line[pos:])
        rows.append(row)
    return rows


def where(grid: list[list[tuple[str, tuple[int, int, int] | None]]], colour: object) -> list:
    """(column, row) of every braille cell drawn in `colour`."""
    return [
        (c, r)
        for r, row in enumerate(grid)
        for c, (ch, fg) in enumerate(row)
        if fg == colour and '\u2800' < ch <= '\u28ff'
    ]


def test_terminal_shows_the_room_and_the_robot(processes: Any, tmp_path: Path) -> None:
    start_world(processes)
    env = {k: v for k, v in os.environ.items() if k not in ('DISPLAY', 'WAYLAND_DISPLAY')}
    pane = TmuxPane(
        [sys.executable, '-m', 'ros2lite.bundled.rviz2.top_view'], env, tmp_path, cols=100, rows=32
    )
    try:
        # the tree's root as the fixed frame, chosen by itself; the robot where tf puts it;
        # all of it on one screen (a capture may catch a redraw halfway)
        status = 'fixed map  robot 1.00,0.50 17°'
        screen = str(wait_until(lambda: status in (s := pane.screen(colours=True)) and
                                '360 hits' in s and 'pwned' in s and s, 30))  # fmt: skip
        grid = cells(screen)
        hits = where(grid, SCAN)
        robot = where(grid, ROBOT)
        assert len(hits) > 100 and robot
        left, right = min(c for c, _ in hits), max(c for c, _ in hits)
        top, bottom = min(r for _, r in hits), max(r for _, r in hits)
        # the four walls: each side of the box is drawn along most of its length
        width, height = right - left + 1, bottom - top + 1
        assert len({c for c, r in hits if r == top}) > 0.5 * width
        assert len({c for c, r in hits if r == bottom}) > 0.5 * width
        assert len({r for c, r in hits if c == left}) > 0.5 * height
        assert len({r for c, r in hits if c == right}) > 0.5 * height
        # a square room in square dots: 2 dots a column, 4 a row
        assert abs(width * 2 - height * 4) <= 8
        # the robot (a 0.2 m circle) at (1.0, 0.5) in the room of x, y in [-2, 2]
        rc = sum(c for c, _ in robot) / len(robot)
        rr = sum(r for _, r in robot) / len(robot)
        assert abs(rc - (left + (X + 2) / 4 * (right - left))) <= 2, (rc, left, right)
        assert abs(rr - (top + (2 - Y) / 4 * (bottom - top))) <= 2, (rr, top, bottom)
        # the hostile frame's name is shown escaped and never retitles the pane
        text = pane.screen()
        assert 'evil\\x1b]2;pwned\\x07' in text
        assert 'pwned' not in pane.title()

        # keys: zoom in by 1.5 (the status line's scale, rounded to 3 digits, follows)
        def scale(text: str) -> float | None:
            found = re.search(r'([0-9.]+) m/dot  (fit|fixed view)', text)
            return float(found.group(1)) if found else None

        before = scale(text)
        assert before is not None
        pane.keys('+')
        after = wait_until(lambda: 'fixed view' in (t := pane.screen()) and scale(t), 10)
        assert abs(before / after - 1.5) < 0.03, (before, after)
        pane.keys('q')
        assert pane.exit_status() == 0
    finally:
        pane.close()


def colour_box(img: Image, colour: tuple[int, int, int]) -> list[tuple[int, int]]:
    """(x, y) of every pixel of exactly `colour`."""
    want = bytes(colour)
    rgb = img.rgb
    out = []
    i = rgb.find(want)
    while i >= 0:
        if i % 3 == 0:
            out.append((i // 3 % img.width, i // 3 // img.width))
            i = rgb.find(want, i + 3)
        else:
            i = rgb.find(want, i + 1)
    return out


def test_window_shows_the_room_and_the_robot(processes: Any, xdisplay: str, tmp_path: Path) -> None:
    start_world(processes)
    env = {**os.environ, 'DISPLAY': xdisplay}
    proc = processes.start(
        [sys.executable, '-m', 'ros2lite.bundled.rviz2.top_window', '--no-frames'], env=env
    )

    def ready() -> Image | None:
        img = screenshot(xdisplay)
        return img if len(colour_box(img, SCAN)) > 300 and colour_box(img, ROBOT) else None

    img = wait_until(ready, 40)
    img.save_png(str(tmp_path / 'top_window.png'))
    hits = colour_box(img, SCAN)
    robot = colour_box(img, ROBOT)
    left, right = min(x for x, _ in hits), max(x for x, _ in hits)
    top, bottom = min(y for _, y in hits), max(y for _, y in hits)
    assert abs((right - left) - (bottom - top)) <= 6  # the square room, square
    rx = sum(x for x, _ in robot) / len(robot)
    ry = sum(y for _, y in robot) / len(robot)
    assert abs(rx - (left + (X + 2) / 4 * (right - left))) <= 6, (rx, left, right)
    assert abs(ry - (top + (2 - Y) / 4 * (bottom - top))) <= 6, (ry, top, bottom)
    # inside the room, away from the robot: the background
    assert img.pixel((left + right) // 2 - 40, (top + bottom) // 2 + 40) == BACKGROUND
    assert proc.poll() is None
