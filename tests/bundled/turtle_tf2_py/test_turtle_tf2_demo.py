"""`ros2lite launch turtle_tf2_py turtle_tf2_demo.launch.py`: turtlesim, a broadcaster per
turtle and the listener; turtle2 is spawned and drives up to turtle1."""

from __future__ import annotations

from typing import Any

from tests.bundled.tf2_ros.test_tf2_ros import read_until
from tests.bundled.turtle_tf2_py.following import assert_turtle2_follows_turtle1


def test_turtle2_follows_turtle1(processes: Any, ros_context: Any) -> None:
    launch = processes.cli('launch', 'turtle_tf2_py', 'turtle_tf2_demo.launch.py', env=_headless())
    assert_turtle2_follows_turtle1(ros_context)
    out, err = processes.stop(launch)
    assert 'Successfully spawned turtle2' in out + err


def test_turtle2_follows_a_fixed_frame_beside_turtle1(processes: Any, ros_context: Any) -> None:
    launch = processes.cli(
        'launch', 'turtle_tf2_py', 'turtle_tf2_fixed_frame_demo.launch.py', env=_headless()
    )
    # carrot1 is 2 m to turtle1's left; turtle2 drives there, not onto turtle1
    assert_turtle2_follows_turtle1(ros_context, offset=(0.0, 2.0))
    processes.stop(launch)


def test_static_turtle_broadcaster(processes: Any) -> None:
    processes.cli(
        'run', 'turtle_tf2_py', 'static_turtle_tf2_broadcaster', 'mystaticturtle', '0', '0', '1',
        '0', '0', '1.5707963267948966',
    )  # fmt: skip
    echo = processes.cli('run', 'tf2_ros', 'tf2_echo', 'world', 'mystaticturtle')
    block = read_until(echo, '  0.000  0.000  0.000  1.000\n')
    assert '- Rotation: in RPY (degree) [0.000, -0.000, 90.000]\n' in block, block
    processes.stop(echo)


def _headless() -> dict[str, str]:
    import os

    return {k: v for k, v in os.environ.items() if k not in ('DISPLAY', 'WAYLAND_DISPLAY')}
