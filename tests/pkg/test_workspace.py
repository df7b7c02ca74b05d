"""Finding source workspaces and their packages by colcon's rules."""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

import pytest

from ros2lite.pkg.workspace import enclosing_workspace, scan_workspace, workspaces
from tests.pkg.workspaces import write_package


def test_scan_follows_colcon_rules(tmp_path: Path) -> None:
    src = tmp_path / 'src'
    write_package(src / 'repo' / 'a', 'a')
    write_package(src / 'b', 'b', build_type='ament_cmake')
    write_package(src / 'b' / 'nested_in_b', 'hidden_by_b')  # not looked for inside a package
    write_package(src / 'ignored' / 'c', 'c')
    (src / 'ignored' / 'COLCON_IGNORE').write_text('')
    write_package(src / '.hidden' / 'd', 'd')
    write_package(src / 'dup', 'a')
    (src / 'broken').mkdir()
    (src / 'broken' / 'package.xml').write_text('<package><name>bad name</name></package>')
    (src / 'loop').symlink_to(src, target_is_directory=True)
    scan = scan_workspace(src)
    assert sorted(scan.packages) == ['a', 'b']
    assert scan.packages['a'].directory == src / 'dup'  # the first one in name order
    assert any("duplicate package 'a'" in str(p) for p in scan.problems)
    assert any("invalid package name 'bad name'" in str(p) for p in scan.problems)


def test_enclosing_workspace(tmp_path: Path) -> None:
    ws = tmp_path / 'ws'
    pkg = write_package(ws / 'src' / 'py_pubsub', 'py_pubsub')
    assert enclosing_workspace(pkg / 'py_pubsub') == ws
    assert enclosing_workspace(ws) == ws
    assert enclosing_workspace(tmp_path) is None
    (tmp_path / 'src').mkdir()  # a src/ without packages is not a workspace
    assert enclosing_workspace(tmp_path) is None


def test_a_folder_above_is_a_workspace_only_when_it_looks_made_for_it(tmp_path: Path) -> None:
    """Standing in ~/projects/x, a ~/src holding some package does not make ~ a workspace
    (it used to, and its packages shadowed the bundled demos); standing inside its src/, or
    anywhere in it once colcon has built it, does."""
    home = tmp_path / 'home'
    write_package(home / 'src' / 'demo_nodes_py', 'demo_nodes_py')
    elsewhere = home / 'projects' / 'x'
    elsewhere.mkdir(parents=True)
    assert enclosing_workspace(elsewhere) is None
    assert workspaces({}, elsewhere) == []
    assert enclosing_workspace(home) == home  # standing in it
    assert enclosing_workspace(home / 'src' / 'demo_nodes_py') == home  # inside its sources
    (home / 'log').mkdir()
    assert enclosing_workspace(elsewhere) is None  # a bare log/ is not colcon's
    (home / 'log' / 'COLCON_IGNORE').write_text('')
    assert enclosing_workspace(elsewhere) == home


def test_workspaces_in_order(tmp_path: Path) -> None:
    here = tmp_path / 'here'
    write_package(here / 'src' / 'p', 'p')
    other = tmp_path / 'other'
    env = {'ROS2LITE_WORKSPACE': os.pathsep.join([str(other), str(here), ''])}
    assert workspaces(env, here / 'src') == [here, other]
    assert workspaces({}, tmp_path) == []


@pytest.mark.parametrize('layout', ['src', 'flat'])
def test_workspace_entry_with_or_without_src(tmp_path: Path, layout: str) -> None:
    from ros2lite.pkg.index import PackageIndex

    root = tmp_path / 'ws'
    write_package((root / 'src' if layout == 'src' else root) / 'p', 'p')
    index = PackageIndex({'ROS2LITE_WORKSPACE': str(root)}, cwd=tmp_path)
    pkg = index.find('p')
    assert pkg is not None and pkg.origin == 'workspace'


# -- ros2lite's own files are never a workspace -----------------------------------------------

REPO = Path(__file__).resolve().parents[2]


@pytest.fixture(scope='module')
def cloned_home(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A home whose `~/ros2_ws/src/ros2lite` is this checkout (its tracked files, as a clone
    holds them once committed: the working tree's files, new ones too), beside a package the
    user wrote."""
    import shutil
    import subprocess

    home = tmp_path_factory.mktemp('home')
    clone = home / 'ros2_ws' / 'src' / 'ros2lite'
    listed = subprocess.run(
        ['git', 'ls-files', '-z', '--cached', '--others', '--exclude-standard'],
        cwd=REPO,
        capture_output=True,
        check=True,
    ).stdout.decode()
    for rel in filter(None, listed.split('\0')):
        if (REPO / rel).is_file():
            (clone / rel).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(REPO / rel, clone / rel)
    write_package(
        home / 'ros2_ws' / 'src' / 'py_pubsub',
        'py_pubsub',
        scripts={'talker': 'py_pubsub.publisher_member_function:main'},
    )
    return home


def _cli(home: Path, cwd: Path, *args: str) -> tuple[int, str, str]:
    import subprocess
    import sys

    env = {**os.environ, 'HOME': str(home)}
    env.pop('ROS2LITE_WORKSPACE', None)
    proc = subprocess.run(
        [sys.executable, '-m', 'ros2lite', *args],
        cwd=cwd,
        env=env,
        capture_output=True,
        text=True,
        timeout=60,
    )
    return proc.returncode, proc.stdout, proc.stderr


@pytest.mark.parametrize(
    'where',
    # in the clone `python -m` runs the clone's own ros2lite; at the workspace root and in a
    # user package, the installed one (which finds the clone's copy in the workspace's src/)
    ['ros2_ws/src/ros2lite', 'ros2_ws', 'ros2_ws/src/py_pubsub', 'ros2_ws/src/ros2lite/ros2lite'],
)
def test_a_checkout_under_a_workspace_hides_no_bundled_package(
    cloned_home: Path, where: str
) -> None:
    """The quick start, typed in a checkout at ~/ros2_ws/src/ros2lite and around it: the
    checkout's bundled package.xml files are not workspace packages, the user's package
    still is, from the root and from inside src/ alike."""
    cwd = cloned_home / where
    code, out, err = _cli(cloned_home, cwd, 'pkg', 'executables', 'demo_nodes_py')
    assert code == 0 and 'demo_nodes_py talker\n' in out, err
    code, out, err = _cli(cloned_home, cwd, 'interface', 'show', 'turtlesim/msg/Pose')
    assert (code, out.splitlines()[:2]) == (0, ['float32 x', 'float32 y']), err
    code, out, err = _cli(cloned_home, cwd, 'pkg', 'prefix', 'turtlesim')
    assert err == 'turtlesim: from the packages bundled with ros2lite\n'
    code, out, err = _cli(cloned_home, cwd, 'pkg', 'executables', 'py_pubsub')
    assert (code, out) == (0, 'py_pubsub talker\n'), err
    code, out, err = _cli(cloned_home, cwd, 'pkg', 'prefix', 'py_pubsub')
    assert err == f'py_pubsub: from the source workspace {cloned_home / "ros2_ws"}\n'


def test_a_checkout_alone_is_no_workspace(tmp_path: Path) -> None:
    """~/src/ros2lite with nothing else in ~/src: standing in it finds no workspace at all."""
    from ros2lite.pkg.workspace import ROS2LITE_ROOT

    checkout = tmp_path / 'src' / 'ros2lite'
    checkout.mkdir(parents=True)
    (checkout / 'ros2lite').symlink_to(ROS2LITE_ROOT, target_is_directory=True)
    assert enclosing_workspace(checkout) is None
    assert enclosing_workspace(tmp_path) is None
    assert workspaces({'ROS2LITE_WORKSPACE': str(ROS2LITE_ROOT / 'bundled')}, tmp_path) == []
    assert scan_workspace(ROS2LITE_ROOT).packages == {}


def test_find_nearby(tmp_path: Path) -> None:
    """Around (cwd and its parents) or just below (its subdirectories): sources by package
    name or by directory, an install/ isolated or merged; workspaces in use are skipped."""
    from ros2lite.pkg.workspace import find_nearby

    ws = tmp_path / 'ros2_ws'
    write_package(ws / 'src' / 'repo' / 'renamed_dir', 'real_name')
    found = find_nearby('real_name', tmp_path)
    assert found is not None and (found.workspace, found.built, found.sources) == (ws, False, True)
    assert find_nearby('real_name', ws / 'src' / 'repo') == found  # from a parent
    assert find_nearby('real_name', tmp_path, in_use=[ws]) is None
    assert find_nearby('absent', tmp_path) is None
    merged = tmp_path / 'merged'
    marker = merged / 'install' / 'share' / 'ament_index' / 'resource_index' / 'packages'
    marker.mkdir(parents=True)
    (marker / 'only_built').write_text('')
    built = find_nearby('only_built', tmp_path)
    assert built is not None and (built.workspace, built.built, built.sources) == (
        merged,
        True,
        False,
    )
    assert built.ways_in() == (
        f'it is built in the workspace {merged}, which this shell has not sourced: '
        f'`source {merged}/install/setup.bash`'
    )


def test_the_quick_start_runs_in_the_clone(
    cloned_home: Path, ros_context: Any, processes: Any
) -> None:
    """`run demo_nodes_py talker` typed in the checkout publishes, and `doctor` there has
    nothing to say about packages."""
    import subprocess
    import sys

    from ros2lite.executors import SingleThreadedExecutor
    from ros2lite.node import Node
    from tests.spinning import spin_until

    clone = cloned_home / 'ros2_ws' / 'src' / 'ros2lite'
    node = Node('clone_probe', context=ros_context)
    got: list[str] = []
    node.create_subscription(
        'std_msgs/msg/String', '/clone_chatter', lambda m: got.append(m.data), 10
    )
    ex = SingleThreadedExecutor(context=ros_context)
    ex.add_node(node)
    env = {**os.environ, 'HOME': str(cloned_home)}
    talker = ['run', 'demo_nodes_py', 'talker', '--ros-args', '-r', 'chatter:=/clone_chatter']
    processes.start(
        [sys.executable, '-m', 'ros2lite', *talker],
        cwd=clone,
        env=env,
        stdin=subprocess.DEVNULL,
        start_new_session=True,
    )
    spin_until(ex, lambda: got, timeout=20)
    assert got[0].startswith('Hello World: ')
    _code, out, err = _cli(cloned_home, clone, 'doctor')
    assert 'workspace package' not in err and 'package' not in out.partition('Failed')[2], err
