"""`ros2lite env`: a child shell of each kind becomes a ROS shell (rclpy and interface
packages import, `ros2` runs ros2lite with tab completion, typed at a real interactive
prompt), and without it nothing named after a ROS package is importable."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest

from ros2lite.node import Node
from tests.bundled.tmux import TmuxPane
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


def _path_without_ros2() -> str:
    """This PATH less any directory holding a `ros2` (a ROS 2 install on the test machine)."""
    dirs = os.environ.get('PATH', os.defpath).split(os.pathsep)
    return os.pathsep.join(d for d in dirs if not (Path(d) / 'ros2').exists())


@pytest.mark.parametrize('shell', ['bash', 'zsh', 'fish'])
def test_ros2_as_printed_with_tab_completion(shell: str, ros_context: Any, tmp_path: Path) -> None:
    """The course's line typed as printed at an interactive prompt after the one step:
    `ros2 to<Tab>` completes to `topic`, `ros2 topic list` lists the live graph, and a
    topic's name completes from it."""
    if shutil.which(shell) is None:
        pytest.skip(f'{shell} is not installed')
    node = Node('shell_probe', context=ros_context, enable_rosout=False)
    node.create_publisher('std_msgs/msg/String', 'ros2_as_printed', 10)
    (tmp_path / '.zshrc').write_text('')  # no zsh new-user menu
    env = {
        **_clean_env(),
        'PATH': _path_without_ros2(),
        'HOME': str(tmp_path),
        'ZDOTDIR': str(tmp_path),
        'XDG_CONFIG_HOME': str(tmp_path / 'config'),
        'XDG_DATA_HOME': str(tmp_path / 'data'),
    }
    argv = {
        'bash': ['bash', '--norc', '--noprofile', '-i'],
        'zsh': ['zsh', '-i'],
        'fish': ['fish', '--no-config', '-i'],
    }[shell]
    step = {
        'bash': f'eval "$({ENV_CMD})"',
        'zsh': f'eval "$({ENV_CMD} --shell zsh)"',
        'fish': f'{ENV_CMD} --shell fish | source',
    }[shell]
    pane = TmuxPane(argv, env, tmp_path, cols=200)

    def shows(text: str) -> str:
        try:
            return pane.wait_for(text)
        except BaseException:
            print(pane.screen())  # what the person would have seen, in the failure report
            raise

    try:
        # the marker is computed, so the typed line itself does not show it
        product = '(math 6 \\* 7)' if shell == 'fish' else '$((6 * 7))'
        pane.keys(step, 'Enter', f'type ros2; echo STEP-{product}', 'Enter')
        shows('STEP-42')
        pane.keys('ros2 to\t')  # a literal tab: what the Tab key sends
        shows('ros2 topic\n')  # completed (tmux drops the space the shell adds after it)
        pane.keys('li\t')
        shows('ros2 topic list\n')
        pane.keys('Enter')
        screen = shows('/ros2_as_printed')
        assert 'command not found' not in screen and 'Unknown command' not in screen
        # names come from the live graph through the function's completion too
        pane.keys('ros2 topic info /ros2_as\t')
        shows('ros2 topic info /ros2_as_printed\n')
    finally:
        pane.close()
        node.destroy_node()


def test_a_real_ros2_is_not_shadowed_unless_asked(tmp_path: Path) -> None:
    """With a ROS 2 `ros2` on PATH the step leaves it alone (and says how to change that in a
    comment); `--ros2` makes `ros2` ros2lite's; a real one that appears later (ROS's setup
    script sourced after the step) takes over from the function."""
    bin_dir = tmp_path / 'ros' / 'bin'
    bin_dir.mkdir(parents=True)
    real = bin_dir / 'ros2'
    real.write_text('#!/bin/sh\necho real ros2 "$@"\n')
    real.chmod(0o755)
    path = _path_without_ros2()
    with_real = {**_clean_env(), 'PATH': f'{bin_dir}{os.pathsep}{path}'}

    def bash(script: str, env: dict[str, str]) -> str:
        proc = subprocess.run(
            ['bash', '-c', script], capture_output=True, text=True, env=env, timeout=60
        )
        assert proc.returncode == 0, proc.stderr
        return proc.stdout

    assert bash(f'eval "$({ENV_CMD})"; ros2 topic', with_real) == 'real ros2 topic\n'
    printed = run_process('env', env={'PATH': with_real['PATH']}).out
    assert f'# ros2 stays {real} (a ROS 2 install)' in printed
    assert 'ros2()' not in printed
    forced = bash(f'eval "$({ENV_CMD} --ros2)"; ros2 --version', with_real)
    assert forced.startswith('ros2lite, version ')
    later = bash(
        f'eval "$({ENV_CMD})"; ros2 --version; PATH={bin_dir}:$PATH; ros2 topic',
        {**_clean_env(), 'PATH': path},
    )
    assert later.startswith('ros2lite, version ') and later.endswith('real ros2 topic\n')
    never = bash(
        f'eval "$({ENV_CMD} --no-ros2)"; type ros2 || echo none', {**with_real, 'PATH': path}
    )
    assert never.endswith('none\n')
