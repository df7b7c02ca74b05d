"""Both ways of working, one package: `pkg create` → real `colcon build` →
`source install/setup.bash` → `ros2lite run`, and the same sources run unbuilt.

colcon-common-extensions comes from PyPI (installed once into pytest's cache directory, or
~/.cache/ros2lite-tests without the cache plugin) and runs with this interpreter, as it does
when installed next to ros2lite.
"""

from __future__ import annotations

import os
import shlex
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest

from ros2lite.executors import SingleThreadedExecutor
from ros2lite.node import Node
from tests.pkg.workspaces import MINIMAL_PUBLISHER
from tests.spinning import spin_until


def _cache_dir(request: pytest.FixtureRequest) -> Path:
    """pytest's cache directory when its cache plugin runs, else the user's cache (so a run
    with `-p no:cacheprovider` does not download colcon again each time)."""
    name = f'colcon-common-extensions-py{sys.version_info[0]}.{sys.version_info[1]}'
    cache = getattr(request.config, 'cache', None)
    if cache is not None:
        return Path(cache.mkdir(name))
    base = Path(os.environ.get('XDG_CACHE_HOME') or Path.home() / '.cache')
    site = base / 'ros2lite-tests' / name
    site.mkdir(parents=True, exist_ok=True)
    return site


@pytest.fixture(scope='session')
def colcon_site(request: pytest.FixtureRequest) -> Path:
    """A directory holding colcon-common-extensions (pip --target), or a skip when PyPI
    cannot be reached."""
    site = _cache_dir(request)
    marker = site / '.installed'
    if not marker.exists():
        done = subprocess.run(
            [
                sys.executable,
                '-m',
                'pip',
                'install',
                '-q',
                '--disable-pip-version-check',
                '--target',
                str(site),
                '--upgrade',
                'colcon-common-extensions',
            ],
            capture_output=True,
            text=True,
            timeout=600,
        )
        if done.returncode != 0:
            pytest.skip(f'colcon-common-extensions could not be installed: {done.stderr[-500:]}')
        marker.write_text('')
    return site


def _bash(script: str, cwd: Path, env: dict[str, str]) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        ['bash', '-c', script], cwd=cwd, env=env, capture_output=True, text=True, timeout=300
    )


@pytest.mark.timeout(900)
def test_create_build_source_run(
    colcon_site: Path, tmp_path: Path, ros_context: Any, processes: Any
) -> None:
    ws = tmp_path / 'ws'
    (ws / 'src').mkdir(parents=True)
    env = {**os.environ}
    env.pop('ROS2LITE_WORKSPACE', None)
    env.pop('AMENT_PREFIX_PATH', None)
    ros2lite = f'{shlex.quote(sys.executable)} -m ros2lite'
    created = _bash(
        f'{ros2lite} pkg create --build-type ament_python --license Apache-2.0 '
        '--node-name talker py_pubsub',
        ws / 'src',
        env,
    )
    assert created.returncode == 0, created.stderr
    (ws / 'src' / 'py_pubsub' / 'py_pubsub' / 'talker.py').write_text(MINIMAL_PUBLISHER)

    build_env = {**env, 'PYTHONPATH': str(colcon_site)}
    built = _bash(f'{shlex.quote(sys.executable)} -m colcon build', ws, build_env)
    assert built.returncode == 0, built.stdout + built.stderr
    script = ws / 'install' / 'py_pubsub' / 'lib' / 'py_pubsub' / 'talker'
    assert script.is_file() and os.access(script, os.X_OK)

    # outside the workspace only the install is seen; inside, the sources shadow it
    outside = _bash(
        f'source install/setup.bash && cd / && {ros2lite} pkg prefix py_pubsub', ws, env
    )
    assert (outside.stdout, outside.stderr) == (f'{ws}/install/py_pubsub\n', '')
    inside = _bash(f'source install/setup.bash && {ros2lite} pkg prefix py_pubsub', ws, env)
    assert inside.stdout == f'{ws}/src/py_pubsub\n'
    assert 'shadows the ament prefix' in inside.stderr

    node = Node('colcon_probe', context=ros_context, enable_rosout=False)
    got: list[str] = []
    node.create_subscription(
        'std_msgs/msg/String', '/colcon_topic', lambda m: got.append(m.data), 10
    )
    ex = SingleThreadedExecutor(context=ros_context)
    ex.add_node(node)
    proc = processes.start(
        [
            'bash',
            '-c',
            f'source {ws}/install/setup.bash && cd / && exec {ros2lite} run '
            'py_pubsub talker --ros-args -r topic:=/colcon_topic',
        ],
        stdin=subprocess.DEVNULL,
        start_new_session=True,
        env=env,
    )
    spin_until(ex, lambda: len(got) >= 2, timeout=30)
    _out, err = processes.stop(proc)
    assert proc.returncode == 0, err
    assert got[0].startswith('Hello World: ')
