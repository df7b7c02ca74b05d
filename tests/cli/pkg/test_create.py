"""`pkg create`: ros2pkg's summary, progress lines, warnings and errors."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import pytest

from tests.cli.conftest import Result


def test_output_of_an_ament_python_package(
    run: Callable[..., Result], tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.chdir(tmp_path)
    result = run(
        'pkg',
        'create',
        '--build-type',
        'ament_python',
        '--license',
        'Apache-2.0',
        'py_pubsub',
        '--dependencies',
        'rclpy',
        'std_msgs',
        '--maintainer-name',
        'student',
        '--maintainer-email',
        's@example.com',
    )
    assert result.code == 0, result.err
    assert result.err == ''
    assert result.out == (
        'going to create a new package\n'
        'package name: py_pubsub\n'
        f'destination directory: {tmp_path}\n'
        'package format: 3\n'
        'version: 0.0.0\n'
        'description: TODO: Package description\n'
        "maintainer: ['student <s@example.com>']\n"
        "licenses: ['Apache-2.0']\n"
        'build type: ament_python\n'
        "dependencies: ['rclpy', 'std_msgs']\n"
        'creating folder ./py_pubsub\n'
        'creating ./py_pubsub/package.xml\n'
        'creating source folder\n'
        'creating folder ./py_pubsub/py_pubsub\n'
        'creating ./py_pubsub/setup.py\n'
        'creating ./py_pubsub/setup.cfg\n'
        'creating folder ./py_pubsub/resource\n'
        'creating ./py_pubsub/resource/py_pubsub\n'
        'creating ./py_pubsub/py_pubsub/__init__.py\n'
        'creating folder ./py_pubsub/test\n'
        'creating ./py_pubsub/test/test_copyright.py\n'
        'creating ./py_pubsub/test/test_flake8.py\n'
        'creating ./py_pubsub/test/test_pep257.py\n'
    )


def test_unknown_license_warning_and_node(run: Callable[..., Result], tmp_path: Path) -> None:
    result = run(
        'pkg',
        'create',
        'my_pkg',
        '--destination-directory',
        str(tmp_path / 'src'),
        '--node-name',
        'my_node',
        '--maintainer-name',
        'u',
        '--maintainer-email',
        'u@todo.todo',
    )
    assert result.code == 0, result.err
    lines = result.out.splitlines()
    assert lines[8:11] == ['build type: ament_cmake', 'dependencies: []', 'node_name: my_node']
    assert f'creating {tmp_path}/src/my_pkg/src/my_node.cpp' in lines
    assert result.out.endswith(
        "\n[WARNING]: Unknown license 'TODO: License declaration'.  This has been set in the "
        'package.xml, but no LICENSE file has been created.\nIt is recommended to use one of '
        'the ament license identifiers:\nApache-2.0\nBSL-1.0\nBSD-2.0\nBSD-2-Clause\n'
        'BSD-3-Clause\nGPL-3.0-only\nLGPL-3.0-only\nMIT\nMIT-0\n'
    )


def test_license_list(run: Callable[..., Result]) -> None:
    result = run('pkg', 'create', 'x', '--license', '?')
    assert result.out.splitlines()[:2] == ['Supported licenses:', 'Apache-2.0']
    assert result.code == 0


def test_errors(run: Callable[..., Result], tmp_path: Path) -> None:
    (tmp_path / 'exists').mkdir()
    result = run('pkg', 'create', 'exists', '--destination-directory', str(tmp_path))
    assert result.code == 1 and result.out == ''
    assert result.err == (
        f'\nAborted!\nThe directory already exists: {tmp_path}/exists\nEither remove the '
        'directory or choose a different destination directory or package name\n'
    )
    bad = run('pkg', 'create', 'Bad-Name', '--destination-directory', str(tmp_path))
    assert bad.code == 1 and 'not a valid package name' in bad.err
    assert not (tmp_path / 'Bad-Name').exists()
    assert run('pkg', 'create', 'x', '--build-type', 'meson').code == 2
