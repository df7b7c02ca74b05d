"""Finding source workspaces and their packages by colcon's rules."""

from __future__ import annotations

import os
from pathlib import Path

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
    assert any("duplicate package 'a'" in p for p in scan.problems)
    assert any("invalid package name 'bad name'" in p for p in scan.problems)


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
