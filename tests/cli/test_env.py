"""`ros2lite env`: a child shell of each kind becomes a ROS shell (rclpy and interface
packages import), and without it nothing named after a ROS package is importable."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from tests.cli.conftest import run_process

ENV_CMD = f'{sys.executable} -m ros2lite env'
PROBE = (
    'import rclpy, std_msgs.msg; from std_msgs.msg import String; '
    'print(rclpy.__name__, String(data="hi").data)'
)


def _clean_env() -> dict[str, str]:
    """The test process's environment without any PYTHONPATH (a fresh terminal's)."""
    return {k: v for k, v in os.environ.items() if k not in ('PYTHONPATH', 'ROS2LITE_PYTHON_SITE')}


@pytest.mark.parametrize(
    'shell, script',
    [
        ('bash', f'eval "$({ENV_CMD})" && {sys.executable} -c \'{PROBE}\''),
        ('zsh', f'eval "$({ENV_CMD} --shell zsh)" && {sys.executable} -c \'{PROBE}\''),
        ('fish', f"{ENV_CMD} --shell fish | source; and {sys.executable} -c '{PROBE}'"),
    ],
)
def test_each_shell_becomes_a_ros_shell(shell: str, script: str) -> None:
    if shutil.which(shell) is None:
        pytest.skip(f'{shell} is not installed')
    proc = subprocess.run(
        [shell, '-c', script], capture_output=True, text=True, env=_clean_env(), timeout=60
    )
    assert (proc.returncode, proc.stdout) == (0, 'rclpy hi\n'), proc.stderr


def test_printed_lines() -> None:
    result = run_process('env')
    compat = Path(__file__).resolve().parents[2] / 'ros2lite' / 'compat'
    assert result.code == 0 and result.err == ''
    assert result.out.startswith(f'export PYTHONPATH={compat}')
    fish = run_process('env', '--shell', 'fish')
    assert fish.out.startswith(f"set -gx PYTHONPATH '{compat}")
    bad = run_process('env', '--shell', 'tcsh')
    assert bad.code == 2 and "'tcsh' is not one of" in bad.err


def test_without_it_no_ros_package_is_shadowed(tmp_path: Path) -> None:
    """A plain `import ros2lite` serves no `rclpy` and no `std_msgs`, and a real ROS
    install on the path (here a stand-in `rclpy`) is the one imported."""
    plain = subprocess.run(
        [sys.executable, '-c', 'import ros2lite, ros2lite.msgs.std_msgs.msg\nimport std_msgs'],
        capture_output=True,
        text=True,
        env=_clean_env(),
        timeout=60,
    )
    assert plain.returncode == 1 and "No module named 'std_msgs'" in plain.stderr
    (tmp_path / 'rclpy').mkdir()
    (tmp_path / 'rclpy' / '__init__.py').write_text('REAL = True\n')
    real = subprocess.run(
        [sys.executable, '-c', 'import ros2lite, rclpy; print(rclpy.REAL)'],
        capture_output=True,
        text=True,
        env={**_clean_env(), 'PYTHONPATH': str(tmp_path)},
        timeout=60,
    )
    assert (real.returncode, real.stdout) == (0, 'True\n'), real.stderr
