"""`pkg list`, `pkg executables`, `pkg prefix`, `pkg xml` over bundled, installed and source
workspace packages."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import pytest

from tests.cli.conftest import Result
from tests.pkg.test_executables import make_ament_prefix
from tests.pkg.workspaces import write_package


@pytest.fixture
def workspace(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """A workspace with a Python package, cwd inside it; an install prefix shadowed by it."""
    ws = tmp_path / 'ws'
    write_package(
        ws / 'src' / 'py_pubsub',
        'py_pubsub',
        scripts={'talker': 'py_pubsub.talker:main', 'listener': 'py_pubsub.listener:main'},
        modules={'py_pubsub/__init__.py': '', 'py_pubsub/talker.py': '', 'launch/a.launch.py': ''},
    )
    prefix = make_ament_prefix(tmp_path / 'install', 'py_pubsub', {'talker': '#!/bin/sh\n'})
    make_ament_prefix(prefix, 'tools', {'b': '#!/bin/sh\n', 'a': '#!/bin/sh\n'})
    monkeypatch.setenv('AMENT_PREFIX_PATH', str(prefix))
    monkeypatch.chdir(ws / 'src' / 'py_pubsub')
    return ws


def test_list(run: Callable[..., Result], workspace: Path) -> None:
    names = run('pkg', 'list').out.splitlines()
    assert names == sorted(names)
    assert {'py_pubsub', 'tools', 'turtlesim', 'demo_nodes_py', 'std_msgs'} <= set(names)


def test_executables(run: Callable[..., Result], workspace: Path) -> None:
    assert run('pkg', 'executables', 'py_pubsub').out == ('py_pubsub listener\npy_pubsub talker\n')
    assert run('pkg', 'executables', 'tools').out == 'tools a\ntools b\n'
    full = run('pkg', 'executables', 'py_pubsub', '--full-path').out.splitlines()
    # a module that is not written yet shows its target instead of a file
    assert full == ['py_pubsub.listener:main', f'{workspace}/src/py_pubsub/py_pubsub/talker.py']
    everything = run('pkg', 'executables').out.splitlines()
    assert 'turtlesim turtlesim_node' in everything and 'tools a' in everything
    missing = run('pkg', 'executables', 'py_pubsb')
    assert missing.code == 1
    assert missing.err == "Package 'py_pubsb' not found; did you mean: py_pubsub?\n"


def test_prefix_names_the_winning_source(run: Callable[..., Result], workspace: Path) -> None:
    result = run('pkg', 'prefix', 'py_pubsub')
    assert result.out == f'{workspace}/src/py_pubsub\n'
    assert result.err == (
        f'py_pubsub: from the source workspace {workspace}; shadows the ament prefix '
        f'{workspace.parent}/install\n'
    )
    installed = run('pkg', 'prefix', 'tools')
    assert (installed.out, installed.err) == (f'{workspace.parent}/install\n', '')
    share = run('pkg', 'prefix', '--share', 'tools')
    assert share.out == f'{workspace.parent}/install/share/tools\n'
    missing = run('pkg', 'prefix', 'nope')
    assert (missing.code, missing.err) == (1, 'Package not found\n')


def test_xml(run: Callable[..., Result], workspace: Path) -> None:
    whole = run('pkg', 'xml', 'py_pubsub')
    assert whole.out.startswith('<package format="3">\n  <name>py_pubsub</name>')
    assert whole.out.endswith('</package>\n')
    assert run('pkg', 'xml', 'py_pubsub', '-t', 'version').out == '1.2.3\n'
    assert run('pkg', 'xml', 'py_pubsub', '--tag', 'nope').err == 'XML tag not found\n'
    assert run('pkg', 'xml', 'tools').err == 'Package XML manifest not found\n'
    assert run('pkg', 'xml', 'nope').err == 'Package not found\n'


def test_xml_of_bundled_packages(run: Callable[..., Result]) -> None:
    # the versions and descriptions of the Jazzy packages they stand for
    assert run('pkg', 'xml', 'demo_nodes_py', '-t', 'version').out == '0.33.5\n'
    assert run('pkg', 'xml', 'std_msgs', '-t', 'version').out == '5.3.6\n'
    assert run('pkg', 'xml', 'rcl_interfaces', '-t', 'version').out == '2.0.3\n'
    assert run('pkg', 'xml', 'nav_msgs', '-t', 'depend').out == (
        'builtin_interfaces\ngeometry_msgs\nstd_msgs\n'
    )


def test_every_bundled_package_has_its_manifest() -> None:
    from ros2lite.pkg.index import ORIGIN_BUNDLED, PackageIndex
    from ros2lite.pkg.manifest import read_manifest

    bundled = [p for p in PackageIndex({}).packages().values() if p.origin == ORIGIN_BUNDLED]
    assert len(bundled) > 30
    for pkg in bundled:
        assert pkg.manifest_path is not None, pkg.name
        assert read_manifest(pkg.manifest_path).name == pkg.name
