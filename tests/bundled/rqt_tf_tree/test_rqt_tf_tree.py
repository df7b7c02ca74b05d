"""`rqt_tf_tree` against a live broadcaster: the tree in tmux (frames in boxes, top down,
edges labelled), in a window under a virtual X display, and as Graphviz text without a
display; and the terminal picture of a known tree, which runs top down through the labels."""

from __future__ import annotations

import os
import sys
import time
from pathlib import Path
from typing import Any

from ros2lite.bundled.rqt_graph.output import NODE_COLOUR
from ros2lite.bundled.rqt_graph.terminal_view import render_lines, render_text
from ros2lite.bundled.tf2_tools.frames import Frame, to_graph
from tests.bundled.screenshot import screenshot
from tests.bundled.tf2_tools.conftest import FRAMES, start_broadcaster
from tests.bundled.tmux import TmuxPane

TF_TREE = [sys.executable, '-m', 'ros2lite', 'run', 'rqt_tf_tree', 'rqt_tf_tree']


def no_display() -> dict[str, str]:
    return {k: v for k, v in os.environ.items() if k not in ('DISPLAY', 'WAYLAND_DISPLAY')}


def test_three_thousand_frames_are_drawn_in_seconds() -> None:
    # the terminal view said "0 frames" at 95 % CPU for 30-40 s with 3,000 frames: the layout
    # (grandalf's) was quadratic, then drawing every edge of a 100,000-column star (56 s)
    frames = tuple(
        Frame(f'sensor_{i}', 'map', 'default_authority', 10000.0, 0.0, 0.0, 0.0)
        for i in range(3000)
    )
    started = time.monotonic()
    rows = render_lines(to_graph(frames), (200, 60))
    assert time.monotonic() - started < 20, time.monotonic() - started
    text = '\n'.join(''.join(ch for ch, _ in row) for row in rows)
    assert len(rows) <= 60 and all(len(row) <= 200 for row in rows)
    # the top-left of the picture: the first frames under the root's long edge row
    assert '│ sensor_0 │' in text and '───' in text


def test_known_tree_top_down() -> None:
    frames = (
        Frame('base_link', 'odom', 'default_authority', 50.0, 4.98, 12.5, 7.5),
        Frame('laser', 'base_link', 'default_authority', 10000.0, 0.0, 0.0, 0.0),
        Frame('camera', 'base_link', 'default_authority', 10000.0, 0.0, 0.0, 0.0),
    )
    lines = render_text(to_graph(frames)).splitlines()

    def row(text: str) -> int:
        return next(i for i, line in enumerate(lines) if text in line)

    assert row('│ odom │') < row('Average rate: 50.0') < row('│ base_link │')
    assert row('│ base_link │') < row('Average rate: 10000.0') < row('│ laser │')
    assert row('│ laser │') == row('│ camera │')  # siblings side by side
    assert row('Most recent transform: 12.5') == row('Average rate: 50.0') + 2
    assert lines[row('│ base_link │') - 2].count('▼') == 1  # one arrow into each frame
    assert '┴' in lines[row('│ base_link │') + 2]  # the fork to its two children


def test_terminal_in_tmux(processes: Any, tmp_path: Path) -> None:
    start_broadcaster(processes)
    pane = TmuxPane(TF_TREE, no_display(), tmp_path, cols=160, rows=45)
    try:
        screen = pane.wait_for('rqt_tf_tree  4 frames')
        screen = pane.wait_for('│ carrot1 │')  # the deepest frame drawn
        lines = screen.splitlines()

        def row(text: str) -> int:
            return next(i for i, line in enumerate(lines) if text in line)

        for frame in FRAMES:
            assert f'│ {frame} │' in screen
        assert row('│ world │') < row('│ turtle1 │') < row('│ carrot1 │')
        assert screen.count('Broadcaster: default_authority') == 3
        assert 'Average rate: 10000.0' in screen  # the static frame
        assert 'Recorded at time: ' in screen
        pane.keys('C-c')
        try:
            assert pane.exit_status() == 0
        except BaseException:
            print(pane.screen())
            raise
    finally:
        pane.close()


def test_window(processes: Any, xdisplay: str) -> None:
    proc = processes.start(TF_TREE, env={**os.environ, 'DISPLAY': xdisplay})
    # no frames yet: the window holds only the 'No tf data received' box
    deadline = time.monotonic() + 20
    while screenshot(xdisplay).count((255, 255, 255), (0, 0, 640, 520)) < 5000:
        assert time.monotonic() < deadline and proc.poll() is None
        time.sleep(0.2)
    shot = screenshot(xdisplay)
    assert shot.count(NODE_COLOUR_RGB, (0, 0, shot.width, shot.height)) == 0
    start_broadcaster(processes)
    while True:  # four frames' ellipses
        shot = screenshot(xdisplay)
        if shot.count(NODE_COLOUR_RGB, (0, 0, shot.width, shot.height)) > 4 * 100:
            break
        assert time.monotonic() < deadline + 10 and proc.poll() is None, proc.poll()
        time.sleep(0.3)
    processes.stop(proc)
    assert proc.returncode == 0


NODE_COLOUR_RGB = (int(NODE_COLOUR[1:3], 16), int(NODE_COLOUR[3:5], 16), int(NODE_COLOUR[5:7], 16))


def test_no_display_prints_the_dot(processes: Any) -> None:
    start_broadcaster(processes)
    proc = processes.start([*TF_TREE, '--display', 'none'], env=no_display())
    out, err = proc.communicate(timeout=30)
    assert proc.returncode == 0, err
    assert out.startswith('digraph G {\n') and '"world" -> "turtle2"' in out
