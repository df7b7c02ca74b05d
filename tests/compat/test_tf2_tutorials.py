"""tf2's Python tutorials, unchanged, in a shell set up by `eval "$(ros2lite env)"`: the
static broadcaster's frame reaches a tf2_echo started after it, and the broadcaster and
listener make turtle2 follow turtle1 in turtlesim."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path
from typing import Any

from tests.bundled.tf2_ros.test_tf2_ros import read_until
from tests.bundled.turtle_tf2_py.following import assert_turtle2_follows_turtle1
from tests.compat.test_tutorials import in_ros_shell


def start(processes: Any, tmp_path: Path, program: str, *args: str) -> Any:
    log = tmp_path / f'{program}{len(processes.procs)}.log'
    env = {
        k: v for k, v in os.environ.items() if k not in ('PYTHONPATH', 'DISPLAY', 'WAYLAND_DISPLAY')
    }
    return processes.start(
        in_ros_shell(program, *args), stdout=log.open('w'), stderr=subprocess.STDOUT, env=env
    )


def test_static_broadcaster_reaches_a_later_tf2_echo(processes: Any, tmp_path: Path) -> None:
    start(processes, tmp_path, 'static_turtle_tf2_broadcaster.py', 'mystaticturtle', '0', '0',
          '1', '0', '0', '0')  # fmt: skip
    echo = processes.cli('run', 'tf2_ros', 'tf2_echo', 'world', 'mystaticturtle')
    block = read_until(echo, '  0.000  0.000  0.000  1.000\n', timeout=60)
    assert block.endswith(
        'At time 0.0\n'
        '- Translation: [0.000, 0.000, 1.000]\n'
        '- Rotation: in Quaternion [0.000, 0.000, 0.000, 1.000]\n'
        '- Rotation: in RPY (radian) [0.000, -0.000, 0.000]\n'
        '- Rotation: in RPY (degree) [0.000, -0.000, 0.000]\n'
        '- Matrix:\n'
        '  1.000  0.000  0.000  0.000\n'
        '  0.000  1.000  0.000  0.000\n'
        '  0.000  0.000  1.000  1.000\n'
        '  0.000  0.000  0.000  1.000\n'
    ), block


def test_broadcaster_and_listener_make_turtle2_follow(
    processes: Any, tmp_path: Path, ros_context: Any
) -> None:
    processes.cli('run', 'turtlesim', 'turtlesim_node', '--display', 'none')
    for turtle in ('turtle1', 'turtle2'):
        start(processes, tmp_path, 'turtle_tf2_broadcaster.py', '--ros-args', '-p',
              f'turtlename:={turtle}')  # fmt: skip
    start(processes, tmp_path, 'turtle_tf2_listener.py')
    assert_turtle2_follows_turtle1(ros_context)


FACES = r'''
import tf2_ros, tf2_ros.buffer, tf2_ros.transform_listener, tf2_ros.transform_broadcaster
import tf2_ros.static_transform_broadcaster, rclpy.time
import ros2lite.tf2 as lib
assert tf2_ros.buffer.Buffer is tf2_ros.Buffer is lib.Buffer
assert tf2_ros.transform_listener.TransformListener is lib.TransformListener
assert tf2_ros.transform_broadcaster.TransformBroadcaster is lib.TransformBroadcaster
assert tf2_ros.static_transform_broadcaster.StaticTransformBroadcaster is (
    lib.StaticTransformBroadcaster
)
for name in ('TransformException', 'LookupException', 'ConnectivityException',
             'ExtrapolationException', 'InvalidArgumentException', 'TimeoutException'):
    assert getattr(tf2_ros, name) is getattr(lib, name)
    assert issubclass(getattr(tf2_ros, name), tf2_ros.TransformException)
print(rclpy.time.Duration(seconds=5.0).nanoseconds)
'''


def test_tf2_ros_faces_are_the_library() -> None:
    env = {k: v for k, v in os.environ.items() if k != 'PYTHONPATH'}
    line = f'eval "$({sys.executable} -m ros2lite env)" && exec {sys.executable} -c "$0"'
    done = subprocess.run(
        ['bash', '-c', line, FACES], capture_output=True, text=True, env=env, timeout=60
    )
    assert (done.returncode, done.stdout) == (0, '5000000000\n'), done.stderr
