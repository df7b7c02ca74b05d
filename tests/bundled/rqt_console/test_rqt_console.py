"""`rqt_console` against a node logging to /rosout: the window under a virtual X display
(a WARN row shows within a second), the terminal table in tmux (colours, keys), and plain
lines without a display."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

from ros2lite.bundled.rqt_console.model import TINTS
from ros2lite.node import Node
from tests.bundled.screenshot import parse_xwd
from tests.bundled.tmux import TmuxPane
from tests.spinning import wait_until

CONSOLE = [sys.executable, '-m', 'ros2lite', 'run', 'rqt_console', 'rqt_console']


def no_display() -> dict[str, str]:
    return {k: v for k, v in os.environ.items() if k not in ('DISPLAY', 'WAYLAND_DISPLAY')}


def listening(node: Node) -> None:
    """Until the console's subscription to /rosout is in the graph the node sees."""
    wait_until(lambda: node.count_subscribers('/rosout') >= 1, timeout=20)


def test_window_shows_a_warning_within_a_second(
    ros_context: Any, processes: Any, xdisplay: str, tmp_path: Path
) -> None:
    warn_tint = TINTS['WARN']
    proc = processes.start(CONSOLE, env={**os.environ, 'DISPLAY': xdisplay})
    node = Node('battery_monitor', context=ros_context)
    try:
        listening(node)
        xwd = shutil.which('xwd')
        assert xwd

        def capture() -> tuple[float, Any]:
            data = subprocess.run(
                [xwd, '-root', '-silent', '-display', xdisplay], capture_output=True, check=True
            ).stdout
            return time.monotonic(), parse_xwd(data)

        # the window is up (its table is white) and no row is tinted yet
        _, shot = wait_until(
            lambda: (s := capture())[1].count((255, 255, 255), (0, 0, 640, 520)) > 20_000 and s
        )
        assert shot.count(warn_tint, (0, 0, shot.width, shot.height)) == 0
        said = time.monotonic()
        node.get_logger().warning('low battery 12%')
        while True:
            seen, shot = capture()
            tinted = shot.count(warn_tint, (0, 0, shot.width, shot.height))
            if tinted > 3_000:  # a row of the table, across the screen
                break
            assert seen - said < 5 and proc.poll() is None, (tinted, proc.poll())
        shot.save_png(str(tmp_path / 'rqt_console.png'))  # to look at
        assert seen - said < 1.0, f'the WARN row showed {seen - said:.2f} s after it was logged'
    finally:
        node.destroy_node()
    processes.stop(proc)
    assert proc.returncode == 0


def test_terminal_table_in_tmux(ros_context: Any, tmp_path: Path) -> None:
    pane = TmuxPane(CONSOLE, no_display(), tmp_path)
    node = Node('battery_monitor', context=ros_context)
    try:
        pane.wait_for('rqt_console  (p pause')
        listening(node)
        node.get_logger().info('all systems nominal')
        node.get_logger().warning('low battery 12%')
        screen = pane.wait_for('low battery 12%')
        assert 'all systems nominal' in screen and 'Displaying 2 of 2 messages' in screen
        warn_line = next(x for x in pane.screen(colours=True).splitlines() if 'low battery' in x)
        r, g, b = TINTS['WARN']
        assert f'48;2;{r};{g};{b}m' in warn_line  # the severity cell is tinted
        assert 'WARN' in warn_line and '/battery_monitor' not in warn_line  # logger name
        assert 'battery_monitor' in warn_line

        pane.keys('3')  # WARN and worse
        screen = pane.wait_for('severity >= WARN')
        assert 'low battery' in screen and 'all systems nominal' not in screen
        pane.keys('p')
        pane.wait_for('PAUSED')
        node.get_logger().error('motor stalled')
        pane.keys('p')
        pane.wait_for('motor stalled')
        pane.keys('/', 'motor', 'Enter')
        screen = pane.wait_for("text ~ 'motor'")
        assert 'motor stalled' in screen and 'low battery' not in screen
        pane.keys('q')
        assert pane.exit_status() == 0
        assert 'Traceback' not in pane.screen()
    finally:
        node.destroy_node()
        pane.close()


# what a hostile node may log: OSC 0 (retitles the terminal), CSI 2J (blanks it), a bidi
# override, BEL
HOSTILE = 'pwn \x1b]0;PWNED\x07 then \x1b[2J\x1b[H and \u202e end'


def test_hostile_rosout_text_is_shown_not_obeyed(ros_context: Any, tmp_path: Path) -> None:
    pane = TmuxPane(CONSOLE, no_display(), tmp_path)
    node = Node('intruder', context=ros_context)
    try:
        pane.wait_for('rqt_console  (p pause')
        before = pane.title()
        listening(node)
        node.get_logger().warning(HOSTILE)
        node.get_logger().warning('after it')
        screen = pane.wait_for('after it')
        # the sequences are written as text, the table is still there, the title unchanged
        assert 'pwn \\x1b]0;PWNED\\x07 then \\x1b[2J\\x1b[H and \\u202e end' in screen
        assert 'Displaying 2 of 2 messages' in screen and 'rqt_console  (p pause' in screen
        assert pane.title() == before and 'PWNED' not in pane.title()
        pane.keys('q')
        assert pane.exit_status() == 0
    finally:
        node.destroy_node()
        pane.close()


def test_plain_lines_without_a_display(ros_context: Any, processes: Any) -> None:
    proc = processes.start([*CONSOLE, '--display', 'none', '--severity', 'warn'], env=no_display())
    node = Node('battery_monitor', context=ros_context)
    try:
        listening(node)
        node.get_logger().info('all systems nominal')
        node.get_logger().warning('low battery 12%')
        assert proc.stdout is not None
        first = proc.stdout.readline()  # the INFO before it is filtered out
        assert first.split()[1:3] == ['WARN', 'battery_monitor'] and 'low battery 12%' in first
        node.get_logger().error(HOSTILE)
        hostile = proc.stdout.readline()
        assert '\x1b' not in hostile and '\x07' not in hostile and '\u202e' not in hostile
        assert 'pwn \\x1b]0;PWNED\\x07 then' in hostile
    finally:
        node.destroy_node()
    out, err = processes.stop(proc)
    assert proc.returncode == 0 and 'nominal' not in out and 'Traceback' not in err


def test_bad_arguments() -> None:
    done = subprocess.run([*CONSOLE, '--severity', 'LOUD'], capture_output=True, text=True)
    assert done.returncode == 2
    assert "unknown severity 'LOUD'" in done.stderr and 'Traceback' not in done.stderr
    done = subprocess.run([*CONSOLE, '--lines', '0'], capture_output=True, text=True)
    assert done.returncode == 2 and "'0' is not a whole number" in done.stderr
