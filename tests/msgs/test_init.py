"""Where interface packages come from, and the import hooks: `ros2lite.msgs.<pkg>` always;
top-level `<pkg>` only once installed (by the compat directory), never shadowing the rest."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from ros2lite.msgs import search_root_dirs


def test_search_order(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv('ROS2LITE_INTERFACE_PATH', f'/first{os.pathsep}/second')
    monkeypatch.setenv('AMENT_PREFIX_PATH', '/opt/ros/jazzy')
    roots = search_root_dirs()
    assert roots[:3] == ['/first', '/second', '/opt/ros/jazzy/share']
    assert Path(roots[3]) == Path(__file__).resolve().parents[2] / 'ros2lite' / 'msgs'


def _python(code: str, **env: str) -> subprocess.CompletedProcess[str]:
    clean = {k: v for k, v in os.environ.items() if k != 'PYTHONPATH'}
    return subprocess.run(
        [sys.executable, '-c', code],
        capture_output=True,
        text=True,
        timeout=60,
        env={**clean, **env},
    )


def test_top_level_hook(tmp_path: Path) -> None:
    """Installed, it serves every package (a user's too) as `<pkg>.msg`, the same classes
    as `ros2lite.msgs.<pkg>`; a Python package of the same name keeps its other modules."""
    (tmp_path / 'mine' / 'msg').mkdir(parents=True)
    (tmp_path / 'mine' / 'msg' / 'Point2.msg').write_text('float64 x\nfloat64 y\n')
    (tmp_path / 'py' / 'mine').mkdir(parents=True)
    (tmp_path / 'py' / 'mine' / '__init__.py').write_text('')
    (tmp_path / 'py' / 'mine' / 'helpers.py').write_text('ANSWER = 42\n')
    code = (
        'from ros2lite.msgs import install_top_level\n'
        'install_top_level()\n'
        'import std_msgs.msg, ros2lite.msgs.std_msgs.msg as ours\n'
        'assert std_msgs.msg.String is ours.String\n'
        'from mine.msg import Point2\n'
        'from mine.helpers import ANSWER\n'
        'print(Point2(x=1.0), ANSWER)\n'
        'try:\n'
        '    from std_msgs.msg import Nope\n'
        'except ImportError as e:\n'
        '    print(e)\n'
    )
    out = _python(code, ROS2LITE_INTERFACE_PATH=str(tmp_path), PYTHONPATH=str(tmp_path / 'py'))
    assert out.returncode == 0, out.stderr
    first, second = out.stdout.splitlines()
    assert first == 'mine.msg.Point2(x=1.0, y=0.0) 42'
    assert "cannot import name 'Nope' from 'std_msgs.msg'" in second
    plain = _python('import ros2lite.msgs.std_msgs.msg\nimport std_msgs')
    assert "No module named 'std_msgs'" in plain.stderr  # not without the hook
