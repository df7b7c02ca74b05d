"""`turtlesim_node`'s own arguments and quiet headless runs: with neither a display nor a
terminal nothing but the log lines is written; a display that cannot open is one line."""

from __future__ import annotations

import os
import subprocess
import sys
from typing import Any

from tests.bundled.turtlesim.conftest import start_turtlesim


def test_no_display_no_terminal_means_only_log_lines(processes: Any) -> None:
    saved = {k: os.environ.pop(k, None) for k in ('DISPLAY', 'WAYLAND_DISPLAY')}
    try:
        proc, lines = start_turtlesim(processes)  # auto: stdout is a pipe here
    finally:
        os.environ.update({k: v for k, v in saved.items() if v is not None})
    out, err = processes.stop(proc)
    assert proc.returncode == 0
    assert out == ''  # no canvas, no escape codes
    assert all(line.startswith('[INFO] [') for line in lines + err.splitlines()), err


def test_bad_display_arguments() -> None:
    env = {k: v for k, v in os.environ.items() if k not in ('DISPLAY', 'WAYLAND_DISPLAY')}
    cmd = [sys.executable, '-m', 'ros2lite', 'run', 'turtlesim', 'turtlesim_node']
    bad = subprocess.run([*cmd, '--display', 'hologram'], capture_output=True, text=True, env=env)
    assert bad.returncode == 2 and "invalid choice: 'hologram'" in bad.stderr
    assert 'Traceback' not in bad.stderr
    window = subprocess.run(
        [*cmd, '--display', 'window'], capture_output=True, text=True, env=env, timeout=60
    )
    assert window.returncode == 1
    assert window.stderr.splitlines()[-2:] == [
        'cannot open a window: no display (DISPLAY is not set)',
        '[ros2run]: Process exited with failure 1',
    ]
    terminal = subprocess.run(
        [*cmd, '--display', 'terminal'], capture_output=True, text=True, env=env, timeout=60
    )
    assert terminal.returncode == 1
    assert 'cannot draw on the terminal: standard output is not a terminal' in terminal.stderr
