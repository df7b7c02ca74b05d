"""Both ways of working, one package: `pkg create` → real `colcon build` →
`source install/setup.bash` → `ros2lite run`, and the same sources run unbuilt; and the
courses' four workspaces under `pip install 'ros2lite[colcon]'`: an ament_python package, an
interface package built without CMake, a package publishing with it, an empty C++ package
named and skipped; `colcon test` on a fresh package.

The colcon extra's requirements (read from ros2lite's own metadata, so they are the
pyproject's) come from PyPI, installed once into pytest's cache directory (or
~/.cache/ros2lite-tests without the cache plugin), and run with this interpreter, as they do
when installed next to ros2lite; ros2lite's colcon plugin is found through its entry points.
"""

from __future__ import annotations

import hashlib
import os
import re
import shlex
import subprocess
import sys
import xml.etree.ElementTree as ET
from importlib.metadata import requires
from pathlib import Path
from typing import Any

import pytest

from ros2lite.executors import SingleThreadedExecutor
from ros2lite.node import Node
from tests.pkg.workspaces import MINIMAL_PUBLISHER
from tests.spinning import spin_until, wait_until

ROS2LITE = f'{shlex.quote(sys.executable)} -m ros2lite'
COLCON = f'{shlex.quote(sys.executable)} -m colcon'


def _extra_requirements() -> list[str]:
    """`ros2lite[colcon]`'s requirements, with their bounds and markers."""
    out = []
    for req in requires('ros2lite') or []:
        spec, _, marker = req.partition(';')
        if 'extra == "colcon"' not in marker:
            continue
        rest = marker.replace('extra == "colcon"', '').strip()
        rest = re.sub(r'^and\s+|\s+and$', '', rest).strip()
        out.append(spec.strip() + (f'; {rest}' if rest else ''))
    return sorted(out)


def _cache_dir(request: pytest.FixtureRequest, requirements: list[str]) -> Path:
    """pytest's cache directory when its cache plugin runs, else the user's cache (so a run
    with `-p no:cacheprovider` does not download colcon again each time); one per set of
    requirements, so a changed bound installs afresh."""
    digest = hashlib.sha256('\n'.join(requirements).encode()).hexdigest()[:12]
    name = f'colcon-extra-py{sys.version_info[0]}.{sys.version_info[1]}-{digest}'
    cache = getattr(request.config, 'cache', None)
    if cache is not None:
        return Path(cache.mkdir(name))
    base = Path(os.environ.get('XDG_CACHE_HOME') or Path.home() / '.cache')
    site = base / 'ros2lite-tests' / name
    site.mkdir(parents=True, exist_ok=True)
    return site


@pytest.fixture(scope='session')
def colcon_site(request: pytest.FixtureRequest) -> Path:
    """A directory holding the colcon extra's packages (pip --target), or a skip when PyPI
    cannot be reached."""
    requirements = _extra_requirements()
    assert any(r.startswith('colcon-common-extensions') for r in requirements), requirements
    site = _cache_dir(request, requirements)
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
                *requirements,
            ],
            capture_output=True,
            text=True,
            timeout=600,
        )
        if done.returncode != 0:
            pytest.skip(f'the colcon extra could not be installed: {done.stderr[-500:]}')
        marker.write_text('')
    return site


def _clean_env() -> dict[str, str]:
    env = {**os.environ}
    for var in (
        'ROS2LITE_WORKSPACE',
        'AMENT_PREFIX_PATH',
        'CMAKE_PREFIX_PATH',
        'COLCON_PREFIX_PATH',
    ):
        env.pop(var, None)
    return env


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
    env = _clean_env()
    ros2lite = ROS2LITE
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


# -- the courses' workspaces under ros2lite[colcon] ---------------------------------------------

AGE_MSG = '# how old, in years\nint64 age\n'
INTERFACES_CMAKE = """cmake_minimum_required(VERSION 3.8)
project(custom_interfaces)

if(CMAKE_COMPILER_IS_GNUCXX OR CMAKE_CXX_COMPILER_ID MATCHES "Clang")
  add_compile_options(-Wall -Wextra -Wpedantic)
endif()

# find dependencies
find_package(ament_cmake REQUIRED)
find_package(rosidl_default_generators REQUIRED)

rosidl_generate_interfaces(${PROJECT_NAME}
  "msg/Age.msg"
  DEPENDENCIES builtin_interfaces
)

ament_package()
"""
INTERFACES_XML = """<?xml version="1.0"?>
<package format="3">
  <name>custom_interfaces</name>
  <version>0.0.0</version>
  <description>The course's message</description>
  <maintainer email="student@example.com">student</maintainer>
  <license>Apache-2.0</license>
  <buildtool_depend>ament_cmake</buildtool_depend>
  <build_depend>rosidl_default_generators</build_depend>
  <depend>builtin_interfaces</depend>
  <exec_depend>rosidl_default_runtime</exec_depend>
  <member_of_group>rosidl_interface_packages</member_of_group>
  <export>
    <build_type>ament_cmake</build_type>
  </export>
</package>
"""
# the course's publisher, written for rclpy: it runs through the compat faces and imports the
# workspace's message by its ROS name
AGE_PUBLISHER = """import rclpy
from rclpy.node import Node

from custom_interfaces.msg import Age


class AgePublisher(Node):

    def __init__(self):
        super().__init__('age_publisher')
        self.publisher_ = self.create_publisher(Age, 'age', 10)
        self.timer = self.create_timer(0.1, self.timer_callback)

    def timer_callback(self):
        msg = Age()
        msg.age = 5
        self.publisher_.publish(msg)


def main(args=None):
    rclpy.init(args=args)
    node = AgePublisher()
    try:
        rclpy.spin(node)
    except KeyboardInterrupt:
        pass
    finally:
        node.destroy_node()
        rclpy.try_shutdown()
"""


BRINGUP_LAUNCH = """from launch import LaunchDescription
from launch_ros.actions import Node


def generate_launch_description():
    return LaunchDescription([Node(package='py_pubsub', executable='talker')])
"""
BRINGUP_CMAKE = """cmake_minimum_required(VERSION 3.8)
project(my_robot_bringup)

find_package(ament_cmake REQUIRED)

install(DIRECTORY launch
  DESTINATION share/${PROJECT_NAME}/
)

ament_package()
"""


def _run(
    script: str, cwd: Path, env: dict[str, str], site: Path
) -> subprocess.CompletedProcess[str]:
    """A bash line with the colcon extra importable (as if pip had installed it here)."""
    return _bash(script, cwd, {**env, 'PYTHONPATH': str(site)})


def _create(src: Path, args: str) -> None:
    done = _bash(f'{ROS2LITE} pkg create {args}', src, _clean_env())
    assert done.returncode == 0, done.stderr


class Course:
    """The four-package workspace, built once."""

    def __init__(self, ws: Path, built: subprocess.CompletedProcess[str]) -> None:
        self.ws = ws
        self.built = built
        self.home = ws.parent / 'home'
        self.home.mkdir(exist_ok=True)


@pytest.fixture(scope='module')
def course(colcon_site: Path, tmp_path_factory: pytest.TempPathFactory) -> Course:
    ws = tmp_path_factory.mktemp('course') / 'ros2_ws'
    src = ws / 'src'
    src.mkdir(parents=True)
    _create(src, '--build-type ament_python --license Apache-2.0 --node-name talker py_pubsub')
    (src / 'py_pubsub' / 'py_pubsub' / 'talker.py').write_text(MINIMAL_PUBLISHER)
    ifaces = src / 'custom_interfaces'
    (ifaces / 'msg').mkdir(parents=True)
    (ifaces / 'msg' / 'Age.msg').write_text(AGE_MSG)
    (ifaces / 'CMakeLists.txt').write_text(INTERFACES_CMAKE)
    (ifaces / 'package.xml').write_text(INTERFACES_XML)
    _create(
        src,
        '--build-type ament_python --license Apache-2.0 --dependencies rclpy custom_interfaces '
        '--node-name age_publisher age_publisher',
    )
    (src / 'age_publisher' / 'age_publisher' / 'age_publisher.py').write_text(AGE_PUBLISHER)
    _create(src, '--build-type ament_cmake my_package')
    # a bringup package: ament_cmake that only installs its launch files
    bringup = src / 'my_robot_bringup'
    (bringup / 'launch').mkdir(parents=True)
    (bringup / 'launch' / 'talker.launch.py').write_text(BRINGUP_LAUNCH)
    (bringup / 'package.xml').write_text(
        INTERFACES_XML.replace('custom_interfaces', 'my_robot_bringup')
    )
    (bringup / 'CMakeLists.txt').write_text(BRINGUP_CMAKE)
    built = _run(f'{COLCON} build', ws, _clean_env(), colcon_site)
    return Course(ws, built)


def test_course_workspace_builds_and_skips_cpp_in_one_line(course: Course) -> None:
    out = course.built.stdout + course.built.stderr
    assert course.built.returncode == 0, out
    assert 'Summary: 5 packages finished' in out, out
    assert 'failed' not in out, out
    skipped = [line for line in out.splitlines() if 'my_package' in line and 'skipped' in line]
    assert len(skipped) == 1, out
    assert 'ros2lite runs Python nodes' in skipped[0]
    assert 'ROS 2 install' in skipped[0]
    assert 'Could not find' not in out and 'CMake Error' not in out

    share = course.ws / 'install' / 'custom_interfaces' / 'share'
    assert (share / 'custom_interfaces' / 'msg' / 'Age.msg').read_text() == AGE_MSG
    assert (share / 'custom_interfaces' / 'package.xml').read_text() == INTERFACES_XML
    index = share / 'ament_index' / 'resource_index'
    assert (index / 'packages' / 'custom_interfaces').read_text() == ''
    assert (index / 'rosidl_interfaces' / 'custom_interfaces').read_text() == 'msg/Age.msg\n'
    assert not (course.ws / 'install' / 'my_package').exists()


def test_colcon_list_names_what_each_package_is(course: Course, colcon_site: Path) -> None:
    listed = _run(f'{COLCON} list', course.ws, _clean_env(), colcon_site)
    assert listed.returncode == 0, listed.stderr
    assert listed.stdout.splitlines() == [
        'age_publisher\tsrc/age_publisher\t(ros.ament_python)',
        'custom_interfaces\tsrc/custom_interfaces\t(ros.ament_cmake.interfaces)',
        'my_package\tsrc/my_package\t(ros.ament_cmake.unbuilt)',
        'my_robot_bringup\tsrc/my_robot_bringup\t(ros.ament_cmake.files)',
        'py_pubsub\tsrc/py_pubsub\t(ros.ament_python)',
    ]


def test_sourced_install_shows_the_message_from_home(course: Course) -> None:
    shown = _bash(
        f'source {course.ws}/install/setup.bash && {ROS2LITE} interface show '
        'custom_interfaces/msg/Age',
        course.home,
        _clean_env(),
    )
    assert (shown.stdout, shown.stderr, shown.returncode) == (AGE_MSG, '', 0)


def test_sourced_install_finds_the_bringup_launch_file_from_home(course: Course) -> None:
    launch = course.ws / 'install' / 'my_robot_bringup' / 'share' / 'my_robot_bringup' / 'launch'
    assert (launch / 'talker.launch.py').read_text() == BRINGUP_LAUNCH
    shown = _bash(
        f'source {course.ws}/install/setup.bash && {ROS2LITE} launch my_robot_bringup '
        'talker.launch.py -p',
        course.home,
        _clean_env(),
    )
    assert shown.returncode == 0, shown.stderr
    assert f'({launch}/talker.launch.py)' in shown.stdout
    assert "Node(package='py_pubsub', executable='talker')" in shown.stdout


@pytest.mark.timeout(300)
def test_installed_node_publishes_age_echoed_from_home(
    course: Course, ros_router: str, processes: Any
) -> None:
    setup = f'source {course.ws}/install/setup.bash'
    node = processes.start(
        ['bash', '-c', f'{setup} && exec {ROS2LITE} run age_publisher age_publisher'],
        cwd=course.home,
        env=_clean_env(),
        stdin=subprocess.DEVNULL,
        start_new_session=True,
    )
    # as in the course: echo once the topic is there (before it, echo cannot know its type)
    wait_until(
        lambda: '/age' in _bash(f'{ROS2LITE} topic list', course.home, _clean_env()).stdout,
        timeout=120,
    )
    # bounded: a node that stops publishing fails the test instead of hanging it
    echo = _bash(
        f'{setup} && timeout 120 {ROS2LITE} topic echo /age --once', course.home, _clean_env()
    )
    _out, err = processes.stop(node)
    assert (echo.stdout, echo.returncode) == ('age: 5\n---\n', 0), echo.stderr + err


def test_packages_select_with_symlink_install(
    course: Course, colcon_site: Path, tmp_path: Path
) -> None:
    """`--packages-select` builds the one package; `--symlink-install` links the sources."""
    base = tmp_path / 'install'
    built = _run(
        f'{COLCON} build --packages-select custom_interfaces --symlink-install '
        f'--build-base {tmp_path}/build --install-base {base}',
        course.ws,
        _clean_env(),
        colcon_site,
    )
    assert built.returncode == 0, built.stdout + built.stderr
    assert 'Summary: 1 package finished' in built.stdout
    msg = base / 'custom_interfaces' / 'share' / 'custom_interfaces' / 'msg' / 'Age.msg'
    assert msg.is_symlink()
    assert msg.resolve() == (course.ws / 'src' / 'custom_interfaces' / 'msg' / 'Age.msg')
    assert [p.name for p in base.iterdir() if p.is_dir()] == ['custom_interfaces']


def test_broken_message_names_file_and_line_and_fails_the_build(
    colcon_site: Path, tmp_path: Path
) -> None:
    ws = tmp_path / 'ws'
    ifaces = ws / 'src' / 'custom_interfaces'
    (ifaces / 'msg').mkdir(parents=True)
    (ifaces / 'msg' / 'Age.msg').write_text('int64 age\nfloat99 weight\n')
    (ifaces / 'CMakeLists.txt').write_text(INTERFACES_CMAKE)
    (ifaces / 'package.xml').write_text(INTERFACES_XML)
    _create(ws / 'src', '--build-type ament_cmake --node-name cpp_node cpp_pkg')
    built = _run(f'{COLCON} build --continue-on-error', ws, _clean_env(), colcon_site)
    out = built.stdout + built.stderr
    assert built.returncode != 0, out
    assert f"{ifaces}/msg/Age.msg:2: invalid type name 'float99'" in out
    assert '1 package failed: custom_interfaces' in out
    assert 'Traceback' not in out
    # a package with C++ sources: what it builds, by line, in the one line
    (line,) = [ln for ln in out.splitlines() if 'cpp_pkg:' in ln]
    assert re.search(r'cpp_pkg: a C\+\+ package \(ament_cmake: add_executable \(line \d+\)', line)
    assert 'so it is skipped: build it in a ROS 2 install' in line


@pytest.mark.timeout(600)
def test_colcon_test_on_a_fresh_package(colcon_site: Path, tmp_path: Path) -> None:
    """The three generated tests: flake8 and pep257 pass; the copyright test is skipped until
    the sources carry headers, as ROS generates it; without its skip it checks for real."""
    ws = tmp_path / 'ws'
    (ws / 'src').mkdir(parents=True)
    _create(ws / 'src', '--build-type ament_python --license Apache-2.0 --node-name talker fresh')
    env = _clean_env()
    built = _run(f'{COLCON} build', ws, env, colcon_site)
    assert built.returncode == 0, built.stdout + built.stderr
    tested = _run(f'{COLCON} test', ws, env, colcon_site)
    assert tested.returncode == 0, tested.stdout + tested.stderr
    result = _run(f'{COLCON} test-result --verbose', ws, env, colcon_site)
    assert result.returncode == 0, result.stdout + result.stderr
    assert result.stdout.strip().splitlines()[-1] == (
        'Summary: 3 tests, 0 errors, 0 failures, 1 skipped'
    )
    cases = {
        case.get('name'): [child.tag for child in case]
        for case in ET.parse(ws / 'build' / 'fresh' / 'pytest.xml').iter('testcase')
    }
    assert cases == {'test_copyright': ['skipped'], 'test_flake8': [], 'test_pep257': []}


def test_with_a_ros_install_the_real_ament_cmake_builds(
    course: Course, colcon_site: Path, tmp_path: Path
) -> None:
    """A sourced ROS install (ament_cmake on the prefix path, cmake on PATH): the plugin steps
    aside and colcon-ros claims every ament_cmake package, as on ROS."""
    ros = tmp_path / 'opt' / 'ros' / 'jazzy'
    config = ros / 'share' / 'ament_cmake' / 'cmake' / 'ament_cmakeConfig.cmake'
    config.parent.mkdir(parents=True)
    config.write_text('')
    bin_dir = tmp_path / 'bin'
    bin_dir.mkdir()
    (bin_dir / 'cmake').write_text('#!/bin/sh\nexit 0\n')
    (bin_dir / 'cmake').chmod(0o755)
    env = {**_clean_env(), 'AMENT_PREFIX_PATH': str(ros)}
    env['PATH'] = f'{bin_dir}{os.pathsep}{env["PATH"]}'
    listed = _run(f'{COLCON} list', course.ws, env, colcon_site)
    assert listed.returncode == 0, listed.stderr
    assert 'custom_interfaces\tsrc/custom_interfaces\t(ros.ament_cmake)' in listed.stdout
    assert 'my_package\tsrc/my_package\t(ros.ament_cmake)' in listed.stdout
