"""turtlesim's terminal canvas in a pseudo-terminal, as over SSH with no display: chosen by
itself, fitted to the terminal, in the background colour (live with `param set`), with the
pen trail, the turtles and the log lines above it; Ctrl-C leaves cleanly."""

from __future__ import annotations

import os
import re
from collections.abc import Callable

from tests.bundled.ptyproc import PtyProcess, ros2lite_argv
from tests.cli.conftest import Result


def test_terminal_canvas(run: Callable[..., Result], ros_router: str) -> None:
    env = dict(os.environ)
    env.pop('DISPLAY', None)
    env.pop('WAYLAND_DISPLAY', None)
    env['COLORTERM'] = 'truecolor'  # colours as 24-bit escapes, easy to look for
    proc = PtyProcess(ros2lite_argv('run', 'turtlesim', 'turtlesim_node'), env, rows=30, cols=70)
    try:
        proc.expect(r'TurtleSim  1 turtle')
        proc.expect(r'\[turtlesim\]: Spawning turtle \[turtle1\] at x=\[5\.544445\]')
        # 70 columns and 28 free lines: a 56x56 world, one text line per two pixel rows
        proc.expect('\x1b\\[38;2;69;86;255;48;2;69;86;255m\u2580{56}\x1b\\[0m')
        assert not re.search('\u2580{57}', proc.output)

        start = len(proc.output)
        run('service', 'call', '/turtle1/set_pen', 'turtlesim/srv/SetPen', '{r: 255, b: 0, g: 0}')
        run('service', 'call', '/turtle1/teleport_relative', 'turtlesim/srv/TeleportRelative',
            '{linear: 3.0, angular: 0.0}')  # fmt: skip
        proc.expect(r'2;255;0;0m', start=start)  # the red trail

        start = len(proc.output)
        run('param', 'set', '/turtlesim', 'background_r', '150')
        proc.expect(r'48;2;150;86;255m', start=start)

        start = len(proc.output)
        run('service', 'call', '/spawn', 'turtlesim/srv/Spawn', '{x: 1.0, y: 1.0}')
        proc.expect(r'TurtleSim  2 turtles', start=start)
        proc.expect(r'Spawning turtle \[turtle2\]', start=start)

        proc.send('\x03')
        assert proc.wait() == 0
        assert 'Traceback' not in proc.output
    finally:
        proc.close()
