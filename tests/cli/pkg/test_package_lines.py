"""One line for a package the CLI cannot use: the broken file and its line (run, launch,
pkg executables, doctor), and the two ways into a workspace nearby that holds the package."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import pytest

from tests.cli.conftest import Result, run_process
from tests.pkg.workspaces import write_package

_BAD_SETUP = "from setuptools import setup\n\nsetup(\n    name='bad_setup',\n"
_BAD_ENTRY = (
    'from setuptools import setup\n\n'
    'setup(\n'
    "    name='bad_entry',\n"
    '    entry_points={\n'
    "        'console_scripts': [\n"
    "            'talker = bad_entry.talker:main',\n"
    "            'listener: bad_entry.listener:main',\n"
    '        ],\n'
    '    },\n'
    ')\n'
)
_BAD_XML = '<?xml version="1.0"?>\n<package format="3">\n  <name>bad_xml</name>\n</pakage>\n'
_LAUNCH = (
    'from launch import LaunchDescription\n'
    'from launch_ros.actions import Node\n\n\n'
    'def generate_launch_description():\n'
    "    return LaunchDescription([Node(package='bad_setup', executable='talker')])\n"
)


@pytest.fixture
def clean_env(monkeypatch: pytest.MonkeyPatch) -> None:
    for name in ('ROS2LITE_WORKSPACE', 'AMENT_PREFIX_PATH', 'ROS2LITE_INTERFACE_PATH'):
        monkeypatch.delenv(name, raising=False)


@pytest.fixture
def broken_ws(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, clean_env: None) -> Path:
    """A workspace whose packages colcon would refuse, cwd at its root."""
    ws = tmp_path / 'ros2_ws'
    src = ws / 'src'
    write_package(src / 'bad_setup', 'bad_setup')
    (src / 'bad_setup' / 'setup.py').write_text(_BAD_SETUP)
    write_package(src / 'bad_entry', 'bad_entry')
    (src / 'bad_entry' / 'setup.py').write_text(_BAD_ENTRY)
    write_package(src / 'no_setup', 'no_setup')
    (src / 'no_setup' / 'setup.py').write_text('import setuptools\n')
    (src / 'bad_xml').mkdir()
    (src / 'bad_xml' / 'package.xml').write_text(_BAD_XML)
    write_package(src / 'good', 'good', modules={'launch/bad.launch.py': _LAUNCH})
    write_package(src / 'msgs', 'msgs', build_type='ament_cmake')
    (src / 'msgs' / 'msg').mkdir()
    (src / 'msgs' / 'msg' / 'Age.msg').write_text('int32 years\nfloat64[ oops\n')
    monkeypatch.chdir(ws)
    return src


def test_run_names_the_file_and_line(run: Callable[..., Result], broken_ws: Path) -> None:
    result = run('run', 'bad_setup', 'talker')
    assert (result.code, result.err) == (
        1,
        f"{broken_ws}/bad_setup/setup.py:3: not valid Python: '(' was never closed\n",
    )
    result = run('run', 'bad_entry', 'talker')
    assert (result.code, result.err) == (
        1,
        f"{broken_ws}/bad_entry/setup.py:8: entry point 'listener: bad_entry.listener:main': "
        "expected 'name = package.module:function'\n",
    )
    result = run('run', 'no_setup', 'x')
    assert result.err == (
        f'{broken_ws}/no_setup/setup.py:1: no setup() call: colcon cannot build the package\n'
    )
    result = run('run', 'bad_xml', 'x')
    assert (result.code, result.err) == (
        1,
        f"Package 'bad_xml' not found; {broken_ws}/bad_xml/package.xml:4: not valid XML: "
        'mismatched tag\n',
    )


def test_pkg_executables_fails_on_a_broken_package(
    run: Callable[..., Result], broken_ws: Path
) -> None:
    one = run('pkg', 'executables', 'bad_setup')
    assert (one.code, one.out) == (1, '')
    assert one.err == f"{broken_ws}/bad_setup/setup.py:3: not valid Python: '(' was never closed\n"
    everything = run('pkg', 'executables')
    assert everything.code == 1
    assert 'demo_nodes_py talker\n' in everything.out  # the rest is still listed
    assert everything.err.splitlines() == [
        f'{broken_ws}/bad_xml/package.xml:4: not valid XML: mismatched tag',
        f"{broken_ws}/bad_entry/setup.py:8: entry point 'listener: bad_entry.listener:main': "
        "expected 'name = package.module:function'",
        f"{broken_ws}/bad_setup/setup.py:3: not valid Python: '(' was never closed",
        f'{broken_ws}/no_setup/setup.py:1: no setup() call: colcon cannot build the package',
    ]


def test_launch_names_the_file_and_line(run: Callable[..., Result], broken_ws: Path) -> None:
    result = run_process('launch', 'good', 'bad.launch.py')
    assert result.code == 1
    assert result.out.splitlines()[-1] == (  # launch logs on stdout, as ros2launch
        '[ERROR] [launch]: Caught exception in launch (see debug for traceback): '
        f"{broken_ws}/bad_setup/setup.py:3: not valid Python: '(' was never closed"
    )
    result = run('launch', 'bad_xml', 'any.launch.py')
    assert (result.code, result.err) == (
        1,
        f"Package 'bad_xml' not found; {broken_ws}/bad_xml/package.xml:4: not valid XML: "
        'mismatched tag\n',
    )


def test_interface_names_the_file_and_line(broken_ws: Path) -> None:
    result = run_process('interface', 'show', 'msgs/msg/Age')
    assert (result.code, result.err) == (
        1,
        f"{broken_ws}/msgs/msg/Age.msg:2: invalid type 'float64['\n",
    )


def test_doctor_fails_its_package_check(
    run: Callable[..., Result], broken_ws: Path, ros_router: str
) -> None:
    result = run('doctor')
    lines = result.err.splitlines()
    errors = [line.split('UserWarning: ', 1)[1] for line in lines if 'UserWarning: ERROR: ' in line]
    assert errors == [
        f'ERROR: workspace package skipped: {broken_ws}/bad_xml/package.xml:4: not valid XML: '
        'mismatched tag',
        f"ERROR: workspace package bad_entry: {broken_ws}/bad_entry/setup.py:8: entry point "
        "'listener: bad_entry.listener:main': expected 'name = package.module:function'",
        f"ERROR: workspace package bad_setup: {broken_ws}/bad_setup/setup.py:3: not valid "
        "Python: '(' was never closed",
        f"ERROR: workspace package msgs: {broken_ws}/msgs/msg/Age.msg:2: invalid type 'float64['",
        f'ERROR: workspace package no_setup: {broken_ws}/no_setup/setup.py:1: no setup() call: '
        'colcon cannot build the package',
    ]
    assert 'Failed modules: package' in result.out


# -- a workspace nearby that this shell does not use --------------------------------------------


@pytest.fixture
def home(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, clean_env: None) -> Path:
    """~ holding ~/ros2_ws with a Python package and an interface package; cwd is ~."""
    src = tmp_path / 'ros2_ws' / 'src'
    write_package(src / 'py_pubsub', 'py_pubsub', scripts={'talker': 'py_pubsub.pub:main'})
    write_package(src / 'custom_interfaces', 'custom_interfaces', build_type='ament_cmake')
    (src / 'custom_interfaces' / 'msg').mkdir()
    (src / 'custom_interfaces' / 'msg' / 'Age.msg').write_text('int32 years\n')
    (tmp_path / 'elsewhere').mkdir()
    monkeypatch.chdir(tmp_path)
    return tmp_path


def test_a_workspace_below_names_the_two_ways_in(run: Callable[..., Result], home: Path) -> None:
    ws = home / 'ros2_ws'
    ways = (
        f'it is in the workspace {ws}, which this shell does not use: `colcon build` there '
        f'and `source {ws}/install/setup.bash`, or `export ROS2LITE_WORKSPACE={ws}`\n'
    )
    # (the type system as a process of its own: the in-process one remembers other tests')
    result = run_process('interface', 'show', 'custom_interfaces/msg/Age')
    assert (result.code, result.err) == (1, f"Unknown package 'custom_interfaces'; {ways}")
    result = run('run', 'py_pubsub', 'talker')
    assert (result.code, result.err) == (1, f"Package 'py_pubsub' not found; {ways}")
    assert run('pkg', 'prefix', 'py_pubsub').err == f'Package not found; {ways}'
    assert run('pkg', 'xml', 'custom_interfaces').err == f'Package not found; {ways}'
    # and the second way in works as it says
    result = run_process(
        'interface', 'show', 'custom_interfaces/msg/Age', env={'ROS2LITE_WORKSPACE': str(ws)}
    )
    assert (result.code, result.out) == (0, 'int32 years\n')


def test_a_built_workspace_not_sourced(home: Path) -> None:
    """The course's second shell, in ~ after `colcon build` in ~/ros2_ws without `source`:
    the install/ colcon left is seen, and `source` comes first."""
    ws = home / 'ros2_ws'
    index = ws / 'install' / 'custom_interfaces' / 'share' / 'ament_index' / 'resource_index'
    (index / 'packages').mkdir(parents=True)
    (index / 'packages' / 'custom_interfaces').write_text('')
    (ws / 'install' / 'COLCON_IGNORE').write_text('')
    result = run_process('interface', 'show', 'custom_interfaces/msg/Age')
    assert result.err == (
        f"Unknown package 'custom_interfaces'; it is built in the workspace {ws}, which this "
        f'shell has not sourced: `source {ws}/install/setup.bash`, or '
        f'`export ROS2LITE_WORKSPACE={ws}`\n'
    )


def test_no_workspace_nearby_keeps_ros2cli_words(run: Callable[..., Result], home: Path) -> None:
    import os

    os.chdir(home / 'elsewhere')
    assert run('run', 'py_pubsub', 'talker').err == "Package 'py_pubsub' not found\n"
    assert run_process('interface', 'show', 'custom_interfaces/msg/Age').err == (
        "Unknown package 'custom_interfaces'\n"
    )
