"""xacro, the registry's, as ROS users run it: `ros2lite run xacro xacro file name:=value`
with `$(find pkg)` answered by the package index, and a launch file's `Command(['xacro ',
path])` finding it on PATH with a plain environment; errors stay one line."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from ros2lite.launch.context import LaunchContext
from ros2lite.launch.find_package import FindPackageShare
from ros2lite.launch.substitutions import Command, PathJoinSubstitution
from ros2lite.urdf import parse_urdf
from tests.urdf.robots import bot_workspace


def xacro(ws: Path, *args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, '-m', 'ros2lite', 'run', 'xacro', 'xacro', *args],
        capture_output=True,
        text=True,
        timeout=60,
        cwd=ws,
    )


def test_run_xacro_with_arguments_and_find(tmp_path: Path) -> None:
    ws = bot_workspace(tmp_path)
    done = xacro(ws, 'src/bot_description/urdf/bot.urdf.xacro', 'width:=0.5')
    assert done.returncode == 0, done.stderr
    robot = parse_urdf(done.stdout)
    assert robot.links['base_link'].visuals[0].geometry.size == (0.5, 0.5, 0.1)
    assert robot.links['base_link'].visuals[0].rgba == (1.0, 0.5, 0.0, 1.0)
    assert robot.joints['right_wheel_joint'].xyz == (0.0, -0.25, 0.0)
    missing = xacro(ws, 'none.xacro')
    assert missing.returncode != 0
    assert 'Traceback' not in missing.stderr
    assert 'No such file or directory' in missing.stderr


def test_launch_command_finds_xacro_in_a_plain_environment(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    ws = bot_workspace(tmp_path)
    monkeypatch.chdir(ws)
    # no venv on PATH, no compat directory on PYTHONPATH: the launch supplies both
    context = LaunchContext(environment={'PATH': '/usr/bin:/bin', 'HOME': str(tmp_path)})
    path = PathJoinSubstitution([FindPackageShare('bot_description'), 'urdf', 'bot.urdf.xacro'])
    text = Command(['xacro ', path, ' width:=0.3']).perform(context)
    robot = parse_urdf(text)
    assert robot.joints['left_wheel_joint'].xyz == (0.0, 0.15, 0.0)
