"""The commands `ros2lite env` defines (`ros2lite.pkg.shell`): `rosdep` and `vcs`, when not
installed, answer in one line what they would have done and what to do here; once a real one
is on PATH it runs instead, in every shell."""

from __future__ import annotations

import os
import shutil
import subprocess
from pathlib import Path

import pytest

from ros2lite.pkg.environment import UnknownShellError
from ros2lite.pkg.shell import STAND_INS, command_lines


def _path_without(names: tuple[str, ...]) -> str:
    dirs = os.environ.get('PATH', os.defpath).split(os.pathsep)
    return os.pathsep.join(d for d in dirs if not any((Path(d) / n).exists() for n in names))


def _run(shell: str, lines: str, line: str, path: str) -> subprocess.CompletedProcess[str]:
    if shutil.which(shell) is None:
        pytest.skip(f'{shell} is not installed')
    sep = '; ' if shell == 'fish' else '\n'
    status = 'echo status=$status' if shell == 'fish' else 'echo status=$?'
    return subprocess.run(
        [shell, '-c', f'{lines}{sep}{line}{sep}{status}'],
        capture_output=True,
        text=True,
        env={**os.environ, 'PATH': path},
        timeout=60,
    )


@pytest.mark.parametrize('shell', ['bash', 'zsh', 'fish'])
@pytest.mark.parametrize(
    'name, line',
    [
        ('rosdep', 'rosdep install -i --from-path src --rosdistro jazzy -y'),
        ('vcs', 'vcs import src < /dev/null'),
    ],
)
def test_a_missing_tool_says_what_to_do_in_one_line(shell: str, name: str, line: str) -> None:
    path = _path_without(('rosdep', 'vcs', 'ros2'))
    lines = command_lines(shell, complete_var='_X', env={'PATH': path})
    proc = _run(shell, lines, line, path)
    assert proc.stdout == 'status=1\n'
    assert proc.stderr == STAND_INS[name] + '\n'
    assert proc.stderr.count('\n') == 1 and name in proc.stderr


@pytest.mark.parametrize('shell', ['bash', 'zsh', 'fish'])
def test_a_real_tool_on_path_is_never_shadowed(shell: str, tmp_path: Path) -> None:
    path = _path_without(('rosdep', 'vcs', 'ros2'))
    lines = command_lines(shell, complete_var='_X', env={'PATH': path})
    # installed after the lines were evaluated (pip install vcstool): the real one runs
    (tmp_path / 'vcs').write_text('#!/bin/sh\necho real vcs "$@"\n')
    (tmp_path / 'vcs').chmod(0o755)
    proc = _run(shell, lines, 'vcs import src', f'{tmp_path}{os.pathsep}{path}')
    assert (proc.stdout, proc.stderr) == ('real vcs import src\nstatus=0\n', '')
    # on PATH already when the lines are written: no function at all
    found = command_lines(shell, complete_var='_X', env={'PATH': f'{tmp_path}{os.pathsep}{path}'})
    starts = [line.split('{')[0].split(';')[0] for line in found.splitlines()]
    defined = (
        {'function rosdep', 'rosdep() '} & set(starts),
        {'function vcs', 'vcs() '} & set(starts),
    )
    assert bool(defined[0]) and not defined[1]


def test_unknown_shell_is_one_clear_error() -> None:
    with pytest.raises(UnknownShellError, match='bash, zsh, fish'):
        command_lines('tcsh', complete_var='_X')
