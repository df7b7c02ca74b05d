"""The environment of children started from the package index."""

from __future__ import annotations

import os
from pathlib import Path

from ros2lite.pkg.environment import COMPAT_DIR, child_environment, prepend_path


def test_compat_and_sources_first_each_once(tmp_path: Path) -> None:
    base = {'PYTHONPATH': os.pathsep.join(['/a', str(COMPAT_DIR), '/b']), 'X': '1'}
    env = child_environment(base, pythonpath=['/src/pkg'], workspaces=[tmp_path])
    assert env['PYTHONPATH'].split(os.pathsep) == [str(COMPAT_DIR), '/src/pkg', '/a', '/b']
    assert env['ROS2LITE_WORKSPACE'] == str(tmp_path)
    assert env['X'] == '1' and base['PYTHONPATH'].startswith('/a')  # the base is not changed
    again = child_environment(env, workspaces=[tmp_path])
    assert again['PYTHONPATH'] == env['PYTHONPATH']
    assert again['ROS2LITE_WORKSPACE'] == str(tmp_path)
    assert 'ROS2LITE_WORKSPACE' not in child_environment({})


def test_prepend_path() -> None:
    assert prepend_path('', ['a']) == 'a'
    assert prepend_path(f'b{os.pathsep}a{os.pathsep}', ['a', 'c']) == os.pathsep.join('acb')
    assert (COMPAT_DIR / 'launch' / '__init__.py').is_file()
