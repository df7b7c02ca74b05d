"""Starting a turtlebot3_gazebo launch file for a test, its output collected as it comes."""

from __future__ import annotations

import subprocess
import threading
from typing import Any

from tests.spinning import wait_until


def launch(processes: Any, *args: str, **kw: Any) -> subprocess.Popen[str]:
    """`ros2lite launch turtlebot3_gazebo ARGS`, once the simulator has said it stands; its
    output lines gather in `proc.lines`."""
    proc = processes.cli(
        'launch', 'turtlebot3_gazebo', *args, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, **kw
    )
    lines: list[str] = []
    proc.lines = lines

    def read() -> None:
        assert proc.stdout is not None
        for line in proc.stdout:
            lines.append(line)

    threading.Thread(target=read, daemon=True).start()
    wait_until(lambda: any('2D stand-in' in line for line in lines), timeout=30)
    return proc
