"""R5-I1: a broken `.msg` in an installed interface package (bad syntax, or a link to
/dev/zero): `interface show` said one line, but every node importing the type died with
`cannot import name 'String'`, the file never named. Now a type ros2lite bundles falls back
to the bundled definition with one warning naming the broken file, and any other type's
import error names file and line."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

BUNDLED = Path(__file__).resolve().parents[2] / 'ros2lite' / 'msgs'


def _prefix(root: Path, package: str, files: dict[str, str | None]) -> Path:
    """An ament prefix holding `package` with these msg files (None: a link to /dev/zero)."""
    (root / 'share/ament_index/resource_index/packages').mkdir(parents=True)
    (root / 'share/ament_index/resource_index/packages' / package).touch()
    msg = root / 'share' / package / 'msg'
    msg.mkdir(parents=True)
    for name, text in files.items():
        if text is None:
            (msg / name).symlink_to('/dev/zero')
        else:
            (msg / name).write_text(text)
    return root


def _python(prefix: Path, code: str) -> subprocess.CompletedProcess[str]:
    env = {**os.environ, 'AMENT_PREFIX_PATH': str(prefix), 'ROS2LITE_NO_DAEMON': '1'}
    return subprocess.run(
        [sys.executable, '-c', code], capture_output=True, text=True, env=env, timeout=60
    )


@pytest.mark.parametrize('broken', ['strin g data\n', None])
def test_a_bundled_type_falls_back_with_one_warning(tmp_path: Path, broken: str | None) -> None:
    files: dict[str, str | None] = {
        p.name: p.read_text() for p in (BUNDLED / 'std_msgs' / 'msg').glob('*.msg')
    }
    files['String.msg'] = broken
    prefix = _prefix(tmp_path / 'p', 'std_msgs', files)
    run = _python(
        prefix,
        'from ros2lite.msgs.std_msgs.msg import String\n'
        'from ros2lite.serialization import serialize_message\n'
        "print(serialize_message(String(data='hi')).hex())",
    )
    assert run.returncode == 0, run.stderr
    assert run.stdout.strip() == '0001000003000000686900'
    [line] = [x for x in run.stderr.splitlines() if 'String.msg' in x]
    assert str(prefix / 'share/std_msgs/msg/String.msg') in line
    assert 'using the definition ros2lite bundles for std_msgs/msg/String' in line
    assert ('invalid type name' in line) == (broken is not None), line


def test_another_broken_type_names_its_file_and_line(tmp_path: Path) -> None:
    prefix = _prefix(tmp_path / 'p', 'my_msgs', {'Age.msg': 'int32 years\nfloat6 days\n'})
    run = _python(prefix, 'from ros2lite.msgs.my_msgs.msg import Age')
    assert run.returncode == 1
    last = run.stderr.strip().splitlines()[-1]
    assert last.startswith("ImportError: cannot import name 'Age' from 'ros2lite.msgs.my_msgs.msg'")
    assert f'{prefix}/share/my_msgs/msg/Age.msg:2:' in last, last
