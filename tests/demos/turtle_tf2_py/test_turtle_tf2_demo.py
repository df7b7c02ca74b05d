"""`ros2lite launch turtle_tf2_py turtle_tf2_demo.launch.py`: turtlesim, a broadcaster per
turtle and the listener; turtle2 is spawned and drives up to turtle1."""

from __future__ import annotations

from typing import Any

from tests.demos.turtle_tf2_py.following import assert_turtle2_follows_turtle1


def test_turtle2_follows_turtle1(processes: Any, ros_context: Any) -> None:
    launch = processes.cli('launch', 'turtle_tf2_py', 'turtle_tf2_demo.launch.py', env=_headless())
    assert_turtle2_follows_turtle1(ros_context)
    out, err = processes.stop(launch)
    assert 'Successfully spawned turtle2' in out + err


def _headless() -> dict[str, str]:
    import os

    return {k: v for k, v in os.environ.items() if k not in ('DISPLAY', 'WAYLAND_DISPLAY')}
