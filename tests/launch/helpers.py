"""Running a LaunchService inside the test process, its screen captured."""

from __future__ import annotations

import io
import threading
from pathlib import Path
from typing import Any

from ros2lite.launch import LaunchDescription, LaunchService


def run_launch(
    entities: list[Any], tmp_path: Path, **kw: Any
) -> tuple[int, list[str], LaunchService]:
    """Run `entities` to the end; (status, screen lines, service)."""
    screen = io.StringIO()
    log_dir = tmp_path / 'log'
    log_dir.mkdir(exist_ok=True)
    service = LaunchService(stream=screen, log_dir=log_dir, **kw)
    service.include_launch_description(LaunchDescription(entities))
    # a launch that never ends fails the test in a minute instead of hanging it
    fired = threading.Event()

    def stop() -> None:
        fired.set()
        service.shutdown()

    watchdog = threading.Timer(60.0, stop)
    watchdog.start()
    try:
        code = service.run()
    finally:
        watchdog.cancel()
    assert not fired.is_set(), 'the launch did not end by itself within 60 s'
    return code, screen.getvalue().splitlines(), service


def sh(script: str, **kw: Any) -> Any:
    """An ExecuteProcess running a shell snippet, output to the screen."""
    from ros2lite.launch.execute import ExecuteProcess

    kw.setdefault('output', 'screen')
    return ExecuteProcess(cmd=['sh', '-c', script], **kw)
