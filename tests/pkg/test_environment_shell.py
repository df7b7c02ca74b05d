"""What makes a ROS shell (`ros2lite.pkg.environment`): the compat directory first on
PYTHONPATH, said once however often it is applied, and shell lines that survive any path."""

from __future__ import annotations

import os
import shlex
import subprocess
import sys
from pathlib import Path

import pytest

from ros2lite.pkg.environment import COMPAT_DIR, UnknownShellError, ros_environment, shell_lines


def test_compat_directory_goes_first_and_only_once() -> None:
    first = ros_environment({'PYTHONPATH': f'/a{os.pathsep}/b'})
    parts = first['PYTHONPATH'].split(os.pathsep)
    assert parts == [str(COMPAT_DIR), '/a', '/b']
    again = ros_environment({**first})
    assert again['PYTHONPATH'] == first['PYTHONPATH']
    assert (COMPAT_DIR / 'rclpy' / '__init__.py').is_file()
    assert (COMPAT_DIR / 'sitecustomize.py').is_file()


def test_field_checks_default_to_jazzys_unless_the_shell_chose() -> None:
    assert ros_environment({})['ROS_PYTHON_CHECK_FIELDS'] == '0'
    assert 'ROS_PYTHON_CHECK_FIELDS' not in ros_environment({'ROS_PYTHON_CHECK_FIELDS': '1'})


@pytest.mark.parametrize('shell', ['bash', 'fish'])
def test_lines_survive_awkward_paths(shell: str, tmp_path: Path) -> None:
    """A PYTHONPATH entry with spaces, quotes and `$` comes back byte for byte."""
    if shell == 'fish' and not _have('fish'):
        pytest.skip('fish is not installed')
    odd = str(tmp_path / "it's a $HOME \\ dir")
    lines = shell_lines(shell, {'PYTHONPATH': odd})
    if shell == 'bash':
        script = f'{lines}\nprintf %s "$PYTHONPATH"'
        cmd = ['bash', '-c', script]
    else:
        script = f'{lines}\nprintf %s "$PYTHONPATH"'
        cmd = ['fish', '-c', script]
    out = subprocess.run(cmd, capture_output=True, text=True, check=True).stdout
    assert out.split(os.pathsep) == [str(COMPAT_DIR), odd]


def test_unknown_shell_is_one_clear_error() -> None:
    with pytest.raises(UnknownShellError, match='bash, zsh, fish'):
        shell_lines('tcsh')


def test_another_interpreter_of_the_same_version_finds_ros2lite() -> None:
    """`python3` of the system (ros2lite lives in a venv) still gets rclpy: sitecustomize
    adds where `ros2lite env` said ros2lite is."""
    system = '/usr/bin/python3'
    probe = (
        subprocess.run(
            [system, '-c', 'import sys; print(*sys.version_info[:2], sep=".")'],
            capture_output=True,
            text=True,
        )
        if Path(system).exists()
        else None
    )
    mine = f'{sys.version_info[0]}.{sys.version_info[1]}'
    if (
        probe is None
        or probe.stdout.strip() != mine
        or Path(sys.executable).resolve() == Path(system).resolve()
    ):
        pytest.skip(f'no other Python {mine} on this machine')
    env = {k: v for k, v in os.environ.items() if k != 'PYTHONPATH'}
    env.update(ros_environment(env))
    out = subprocess.run(
        [system, '-c', 'import rclpy, std_msgs.msg; print(std_msgs.msg.String(data="ok").data)'],
        capture_output=True,
        text=True,
        env=env,
        timeout=60,
    )
    assert (out.returncode, out.stdout) == (0, 'ok\n'), out.stderr


def _have(program: str) -> bool:
    import shutil

    return shutil.which(program) is not None


def test_a_workspace_package_never_shadows_what_ros2lite_imports(tmp_path: Path) -> None:
    """R-V1: an interface package named `click` in a workspace took `import click` from the
    CLI itself (AttributeError: module 'click' has no attribute 'Group')."""
    pkg = tmp_path / 'ws' / 'src' / 'click'
    (pkg / 'msg').mkdir(parents=True)
    (pkg / 'package.xml').write_text(
        '<?xml version="1.0"?><package format="3"><name>click</name><version>0.0.1</version>'
        '<description>x</description><maintainer email="a@b.c">a</maintainer>'
        '<license>MIT</license><buildtool_depend>ament_cmake</buildtool_depend>'
        '<export><build_type>ament_cmake</build_type></export></package>\n'
    )
    (pkg / 'msg' / 'Foo.msg').write_text('int32 x\n')
    env = {k: v for k, v in os.environ.items() if k != 'PYTHONPATH'}
    env.update(ros_environment(env))

    def run(*args: str) -> subprocess.CompletedProcess[str]:
        return subprocess.run(
            [sys.executable, *args],
            capture_output=True,
            text=True,
            env=env,
            cwd=tmp_path / 'ws',
            timeout=60,
        )

    cli = run('-m', 'ros2lite', '--help')
    assert cli.returncode == 0 and 'Usage: ros2lite' in cli.stdout, cli.stderr
    probe = run(
        '-c',
        'import click; from ros2lite.msgs.click.msg import Foo; '
        'print(hasattr(click, "command"), Foo(x=3).x)',
    )
    assert probe.stdout == 'True 3\n', probe.stderr


def test_a_shell_started_in_a_workspace_keeps_it_from_anywhere(tmp_path: Path) -> None:
    """Item 3 of issue 32: `eval "$(ros2lite env)"` in the workspace, then `cd ~`: the
    workspace's interface package is still found, in this shell and its children."""
    pkg = tmp_path / 'ros2_ws' / 'src' / 'my_msgs'
    (pkg / 'msg').mkdir(parents=True)
    (pkg / 'package.xml').write_text(
        '<?xml version="1.0"?><package format="3"><name>my_msgs</name><version>0.0.1</version>'
        '<description>x</description><maintainer email="a@b.c">a</maintainer>'
        '<license>MIT</license><buildtool_depend>ament_cmake</buildtool_depend>'
        '<export><build_type>ament_cmake</build_type></export></package>\n'
    )
    (pkg / 'msg' / 'Age.msg').write_text('int32 years\n')
    home = tmp_path / 'home'
    home.mkdir()
    env = {k: v for k, v in os.environ.items() if k not in ('PYTHONPATH', 'ROS2LITE_WORKSPACE')}
    env['HOME'] = str(home)
    ros2lite = f'{shlex.quote(sys.executable)} -m ros2lite'
    script = (
        f'eval "$({ros2lite} env)" && cd ~ && {ros2lite} interface show my_msgs/msg/Age && '
        'printf "%s\\n" "$ROS2LITE_WORKSPACE"'
    )
    proc = subprocess.run(
        ['bash', '-c', script],
        capture_output=True,
        text=True,
        env=env,
        cwd=tmp_path / 'ros2_ws',
        timeout=60,
    )
    assert (proc.returncode, proc.stdout) == (
        0,
        f'int32 years\n{tmp_path / "ros2_ws"}\n',
    ), proc.stderr
    # outside any workspace the lines name none; one already exported is kept behind the new
    plain = shell_lines('bash', {'ROS2LITE_WORKSPACE': '/elsewhere'})
    assert 'ROS2LITE_WORKSPACE' not in plain
    both = shell_lines('bash', {'ROS2LITE_WORKSPACE': '/elsewhere'}, workspaces=[Path('/ws')])
    assert f'export ROS2LITE_WORKSPACE=/ws{os.pathsep}/elsewhere;' in both
