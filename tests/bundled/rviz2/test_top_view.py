"""The scene from above against real nodes — a static map -> odom, a node broadcasting odom ->
base_footprint with the LaserScan, map, plan and URDF of a 4 m square room — as a person sees
it: in tmux (the hits on the room's four walls over the map's wall cells, the robot where it
stands, the plan, a hostile frame name escaped, keys that zoom and quit) and in a window under
a virtual X display (the hits', walls', plan's and the robot's pixels, the robot's URDF box)."""

from __future__ import annotations

import math
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest

from ros2lite.bundled.rviz2.top_view import FREE, OCCUPIED, PATH, ROBOT, SCAN, rviz_config
from ros2lite.bundled.rviz2.top_window import OCCUPIED_PX
from tests.bundled.rviz2.room import BOX
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


Cell = tuple[str, tuple[int, int, int] | None, tuple[int, int, int] | None]


def cells(screen: str) -> list[list[Cell]]:
    """The pane's characters with their colours, foreground and background (capture-pane
    -e)."""
    rows = []
    for line in screen.split('\n'):
        row: list[Cell] = []
        fg: tuple[int, int, int] | None = None
        bg: tuple[int, int, int] | None = None
        pos = 0
        for m in _SGR.finditer(line):
            row.extend((ch, fg, bg) for ch in line[pos : m.start()])
            pos = m.end()
            params = [int(p) if p else 0 for p in m.group(1).split(';')]
            k = 0
            while k < len(params):
                p = params[k]
                if p in (0, 39):
                    fg = None
                if p in (0, 49):
                    bg = None
                if p == 38 and params[k + 1 : k + 2] == [2]:
                    fg = (params[k + 2], params[k + 3], params[k + 4])
                    k += 4
                elif p == 48 and params[k + 1 : k + 2] == [2]:
                    bg = (params[k + 2], params[k + 3], params[k + 4])
                    k += 4
                k += 1
        row.extend((ch, fg, bg) for ch in line[pos:])
        rows.append(row)
    return rows


def where(grid: list[list[Cell]], colour: object) -> list[tuple[int, int]]:
    """(column, row) of every braille cell drawn in `colour`."""
    return [
        (c, r)
        for r, row in enumerate(grid)
        for c, (ch, fg, _) in enumerate(row)
        if fg == colour and '\u2800' < ch <= '\u28ff'
    ]


def one_line_error(processes: Any, argv: list[str], env: dict[str, str], expected: str) -> None:
    proc = processes.start([sys.executable, '-m', *argv], env=env)
    out, err = proc.communicate(timeout=60)
    assert proc.returncode == 1, (out, err)
    assert err.strip() == expected, err


def behind(grid: list[list[Cell]], colour: object) -> set[tuple[int, int]]:
    """(column, row) of every cell of background `colour`."""
    return {
        (c, r) for r, row in enumerate(grid) for c, (_, _, bg) in enumerate(row) if bg == colour
    }


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
                                '360 hits  1 map  1 path' in s and 'pwned' in s
                                and s, 30))  # fmt: skip
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
        # the map's wall cells where the hits are (the walls' cells lie just outside the
        # room: each wall hit is in a wall cell or next to one), free cells inside
        walls = behind(grid, OCCUPIED)
        near = {(c + dc, r + dr) for c, r in walls for dc in (-1, 0, 1) for dr in (-1, 0, 1)}
        assert sum(1 for h in hits if h in near) > 0.9 * len(hits)
        assert ((left + right) // 2, (top + bottom) // 2 + 3) in behind(grid, FREE)
        # the plan, from the robot towards (-1, -1): down and to the left of it
        plan = where(grid, PATH)
        assert len(plan) > 10
        # the robot (its URDF box) at (1.0, 0.5) in the room of x, y in [-2, 2]
        rc = sum(c for c, _ in robot) / len(robot)
        rr = sum(r for _, r in robot) / len(robot)
        assert abs(rc - (left + (X + 2) / 4 * (right - left))) <= 2, (rc, left, right)
        assert abs(rr - (top + (2 - Y) / 4 * (bottom - top))) <= 2, (rr, top, bottom)
        assert min(c for c, _ in plan) < rc - 5 and max(r for _, r in plan) > rr + 5
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
        # 'f' keeps the robot in the middle, at the scale chosen
        pane.keys('f')
        grid = cells(
            str(wait_until(lambda: 'm/dot  follow' in (t := pane.screen(colours=True)) and t, 10))
        )
        robot = where(grid, ROBOT)  # the box and the heading mark ahead of it: a little right
        middle = sum(c for c, _ in robot) / len(robot) if robot else -1
        assert 49 <= middle <= 53, middle
        # a smaller terminal: the picture is fitted to it again ('a' fits everything)
        pane.keys('a')
        pane.resize(60, 20)

        def fitted() -> list[list[Cell]] | None:
            screen = pane.screen(colours=True)  # whole: the status line is drawn last
            grid = cells(screen)
            hits = where(grid, SCAN)
            whole = 'fixed map' in screen and 'm/dot  fit' in screen and where(grid, ROBOT)
            return grid if whole and hits and max(c for c, _ in hits) < 60 else None

        small = wait_until(fitted, 10)
        assert len(small) <= 21  # 20 lines, and the capture's last newline
        hits = where(small, SCAN)
        assert max(r for _, r in hits) - min(r for _, r in hits) < 18
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
        shown = [len(colour_box(img, c)) for c in (SCAN, ROBOT, OCCUPIED_PX, PATH)]
        return img if shown[0] > 300 and shown[2] > 300 and all(shown) else None

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
    # the robot's outline is its URDF box, 0.5 x 0.3 m turned by 17 degrees (a 0.2 m
    # circle would span 0.4 m)
    per_metre = (right - left) / 4.0
    span = (max(x for x, _ in robot) - min(x for x, _ in robot)) / per_metre
    expected = BOX[0] * math.cos(YAW) + BOX[1] * math.sin(YAW)
    assert abs(span - expected) < 0.06, (span, expected)
    # the map: its free cells inside the room, its wall cells just outside the hits
    middle = ((left + right) // 2, (top + bottom) // 2)
    assert img.pixel(middle[0] - 40, middle[1] + 40) == FREE
    height = bottom - top
    for box in ((left - 6, top, left + 2, bottom), (right - 1, top, right + 7, bottom)):
        assert img.count(OCCUPIED_PX, box) > height, box  # a wall's cells, a few px wide
    assert img.count(OCCUPIED_PX, (left, top - 6, right, top + 2)) > right - left
    assert len(colour_box(img, PATH)) > 50
    assert proc.poll() is None
    if shutil.which('xdotool') is None:
        return  # the mouse is driven through xdotool (apt-get install xdotool)

    def mouse(*args: str) -> None:
        subprocess.run(['xdotool', *args], env=env, check=True)

    # the wheel zooms about the pointer: over the robot, it stays put and grows 1.25 x a notch
    mouse('mousemove', str(round(rx)), str(round(ry)), 'click', '4', 'click', '4')

    def robot_now(width: float) -> list[tuple[int, int]] | None:
        found = colour_box(screenshot(xdisplay), ROBOT)
        wide = found and max(x for x, _ in found) - min(x for x, _ in found)
        return found if wide and abs(wide / width - 1.5625) < 0.1 else None

    width = max(x for x, _ in robot) - min(x for x, _ in robot)
    zoomed = wait_until(lambda: robot_now(width), 20)
    zx = sum(x for x, _ in zoomed) / len(zoomed)
    assert abs(zx - rx) < 6, (zx, rx)
    # a drag pans: the robot follows the pointer
    mouse('mousedown', '1', 'mousemove', str(round(rx) - 30), str(round(ry)),
          'mousemove', str(round(rx) - 60), str(round(ry)), 'mouseup', '1')  # fmt: skip

    def dragged() -> bool:
        found = colour_box(screenshot(xdisplay), ROBOT)
        return bool(found) and abs(sum(x for x, _ in found) / len(found) - (zx - 60)) < 6

    wait_until(dragged, 20)


def test_bad_input_is_one_line(processes: Any) -> None:
    env = {k: v for k, v in os.environ.items() if k not in ('DISPLAY', 'WAYLAND_DISPLAY')}
    view = 'ros2lite.bundled.rviz2.top_view'
    one_line_error(processes, [view], env,
                   'cannot draw on the terminal: standard output is not a terminal')  # fmt: skip
    one_line_error(processes, [view, '--robot-radius', '-1'], env,
                   '--robot-radius must be a positive number, not -1.0')  # fmt: skip
    # rviz2 --terminal hands the view's own options on to it
    rviz2 = ['ros2lite.bundled.rviz2.rviz2', '--terminal', '--robot-radius', '-1']
    one_line_error(processes, rviz2, env, '--robot-radius must be a positive number, not -1.0')
    one_line_error(processes, ['ros2lite.bundled.rviz2.top_window'], env,
                   'cannot open a window: no display (DISPLAY is not set)')  # fmt: skip


RVIZ = """Panels: []
Visualization Manager:
  Class: ""
  Displays:
    - Class: rviz_default_plugins/Grid
      Enabled: true
    - Class: rviz_default_plugins/LaserScan
      Enabled: true
      Topic:
        Value: /front/scan
    - Class: rviz_default_plugins/LaserScan
      Enabled: false
      Topic:
        Value: /rear/scan
  Global Options:
    Fixed Frame: odom
"""


def test_an_rviz_file_gives_the_fixed_frame_and_scans(tmp_path: Path) -> None:
    path = tmp_path / 'view.rviz'
    path.write_text(RVIZ)
    assert rviz_config(str(path)) == ('odom', ['/front/scan'])
    path.write_text('just: text\n')
    with pytest.raises(ValueError, match='is not an RViz configuration'):
        rviz_config(str(path))
    with pytest.raises(ValueError, match=r'cannot read .*missing\.rviz: No such file'):
        rviz_config(str(tmp_path / 'missing.rviz'))
