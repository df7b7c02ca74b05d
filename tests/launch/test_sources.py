"""Launch files that include themselves or each other (F3 / R-L1): the cycle is named in one
line and the launch ends at once with status 1, instead of loading forever; includes nested
deeper than the limit say so."""

from __future__ import annotations

import os
import time
from pathlib import Path

import pytest

from ros2lite.launch.actions import MAX_INCLUDE_DEPTH
from tests.cli.conftest import run_process

SELF_PY = '''\
import os
from launch import LaunchDescription
from launch.actions import IncludeLaunchDescription
from launch.launch_description_sources import PythonLaunchDescriptionSource
def generate_launch_description():
    me = PythonLaunchDescriptionSource(os.path.abspath(__file__))
    return LaunchDescription([IncludeLaunchDescription(me)])
'''


def launch(path: Path) -> tuple[int, str, float]:
    started = time.monotonic()
    result = run_process('launch', str(path))
    return result.code, result.out + result.err, time.monotonic() - started


@pytest.mark.parametrize(
    ('files', 'line'),
    [
        ({'self.launch.py': SELF_PY}, "launch file '{d}/self.launch.py' includes itself"),
        (
            {'self.launch.xml': '<launch><include file="$(dirname)/self.launch.xml"/></launch>'},
            "launch file '{d}/self.launch.xml' includes itself",
        ),
        (
            {
                'a.launch.yaml': 'launch:\n- include:\n    file: "$(dirname)/b.launch.yaml"\n',
                'b.launch.yaml': 'launch:\n- include:\n    file: "$(dirname)/a.launch.yaml"\n',
            },
            'launch files include each other in a cycle: '
            '{d}/a.launch.yaml -> {d}/b.launch.yaml -> {d}/a.launch.yaml',
        ),
    ],
)
def test_a_cycle_of_includes_is_named_in_one_line(
    tmp_path: Path, files: dict[str, str], line: str
) -> None:
    for name, text in files.items():
        (tmp_path / name).write_text(text)
    code, out, seconds = launch(tmp_path / next(iter(files)))
    assert code == 1, out
    errors = [x for x in out.splitlines() if '[ERROR]' in x]
    assert len(errors) == 1 and errors[0].endswith(line.format(d=tmp_path)), out
    assert seconds < 20  # (< 1 s here; it never ended before)


def test_includes_nested_too_deep_say_so(tmp_path: Path) -> None:
    n = MAX_INCLUDE_DEPTH + 5
    for i in range(n):
        inner = f'<include file="$(dirname)/f{i + 1}.launch.xml"/>' if i + 1 < n else ''
        (tmp_path / f'f{i}.launch.xml').write_text(f'<launch>{inner}</launch>')
    code, out, _ = launch(tmp_path / 'f0.launch.xml')
    assert code == 1, out
    assert f'launch files are nested more than {MAX_INCLUDE_DEPTH} deep' in out, out
    assert f'f{MAX_INCLUDE_DEPTH}.launch.xml' in out


COUNTDOWN_XML = '''\
<launch>
  <arg name="n" default="6"/>
  <log message="level $(var n)"/>
  <include file="$(dirname)/countdown.launch.xml" if="$(eval '$(var n) > 0')">
    <arg name="n" value="$(eval '$(var n) - 1')"/>
  </include>
</launch>
'''


def test_a_bounded_self_include_is_no_cycle(tmp_path: Path) -> None:
    """R5: a file including itself with `n:=n-1` until a condition ends it was refused as a
    cycle at level 3; the same file with other arguments is recursion, not a cycle."""
    (tmp_path / 'countdown.launch.xml').write_text(COUNTDOWN_XML)
    code, out, _ = launch(tmp_path / 'countdown.launch.xml')
    assert code == 0, out
    levels = [line.rsplit('level ', 1)[1] for line in out.splitlines() if 'level ' in line]
    assert levels == ['6', '5', '4', '3', '2', '1', '0'], out
    assert '[ERROR]' not in out


@pytest.mark.parametrize('target', ['/dev/zero', 'fifo'])
def test_a_python_launch_file_from_outside_is_read_bounded(tmp_path: Path, target: str) -> None:
    """R5-P1: an included launch file that is a link to /dev/zero (or a FIFO) is refused in
    one line, not read until memory runs out (or forever); `launch` itself refuses them."""
    path = tmp_path / 'x.launch.py'
    if target == 'fifo':
        os.mkfifo(path)
    else:
        path.symlink_to(target)
    (tmp_path / 'top.launch.xml').write_text(f'<launch><include file="{path}"/></launch>')
    code, out, seconds = launch(tmp_path / 'top.launch.xml')
    assert code == 1, out
    assert 'not a regular file, so not read as a Python launch file' in out, out
    assert seconds < 20
