"""One clear line for what is not here (C++ packages and executables, Gazebo, rviz's plugins), and
the C++ demo package whose Python twin answers every verb as `run` does."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import pytest

from ros2lite.pkg.index import BUNDLED_PACKAGES
from ros2lite.pkg.not_here import not_here_line
from tests.cli.conftest import Result, run_process
from tests.pkg.workspaces import write_package


@pytest.fixture(autouse=True)
def nowhere(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    for name in ('ROS2LITE_WORKSPACE', 'AMENT_PREFIX_PATH', 'ROS2LITE_INTERFACE_PATH'):
        monkeypatch.delenv(name, raising=False)
    monkeypatch.chdir(tmp_path)


@pytest.mark.parametrize(
    ('args', 'first'),
    [
        (('run', 'ros_gz_bridge', 'parameter_bridge'), "Package 'ros_gz_bridge' not found"),
        (('launch', 'turtlebot3_simulations', 'x.launch.py'), None),
        (('launch', 'gazebo_plugins', 'x.launch.py'), None),
        (('run', 'rviz_default_plugins', 'x'), "Package 'rviz_default_plugins' not found"),
        (('pkg', 'prefix', 'rviz_common'), 'Package not found'),
        (('pkg', 'executables', 'image_tools'), "Package 'image_tools' not found"),
        (('pkg', 'xml', 'examples_rclcpp_minimal_publisher'), 'Package not found'),
    ],
)
def test_not_here_packages(run: Callable[..., Result], args: tuple[str, ...], first: str) -> None:
    result = run(*args)
    package = args[2] if args[0] == 'pkg' else args[1]
    first = first or f"Package '{package}' not found"
    assert (result.code, result.out, result.err) == (1, '', f'{first}; {not_here_line(package)}\n')


def test_a_gazebo_interface(run: Callable[..., Result]) -> None:
    result = run_process('interface', 'show', 'gazebo_msgs/srv/SpawnEntity')
    assert (result.code, result.err) == (
        1,
        f"Unknown package 'gazebo_msgs'; {not_here_line('gazebo_msgs')}\n",
    )


def test_a_launch_file_including_gazebo(run: Callable[..., Result], tmp_path: Path) -> None:
    """The course's launch file finds gazebo_plugins' share: the substitution fails with the
    line."""
    launch = tmp_path / 'world.launch.py'
    launch.write_text(
        'from launch import LaunchDescription\n'
        'from launch.actions import IncludeLaunchDescription\n'
        'from launch.launch_description_sources import PythonLaunchDescriptionSource\n'
        'from launch.substitutions import PathJoinSubstitution\n'
        'from launch_ros.substitutions import FindPackageShare\n\n\n'
        'def generate_launch_description():\n'
        '    gazebo = PathJoinSubstitution(\n'
        "        [FindPackageShare('gazebo_plugins'), 'launch', 'gazebo.launch.py']\n"
        '    )\n'
        '    source = PythonLaunchDescriptionSource(gazebo)\n'
        '    return LaunchDescription([IncludeLaunchDescription(source)])\n'
    )
    result = run_process('launch', str(launch))
    assert result.code == 1
    assert result.out.splitlines()[-1] == (
        '[ERROR] [launch]: Caught exception in launch (see debug for traceback): '
        f"Package 'gazebo_plugins' not found; {not_here_line('gazebo_plugins')}"
    )


def test_a_cpp_package_in_the_workspace(run: Callable[..., Result], tmp_path: Path) -> None:
    pkg = write_package(tmp_path / 'src' / 'cpp_pubsub', 'cpp_pubsub', build_type='ament_cmake')
    (pkg / 'src').mkdir()
    (pkg / 'src' / 'publisher_member_function.cpp').write_text('int main() { return 0; }\n')
    line = (
        'cpp_pubsub is a C++ package (ament_cmake, src/publisher_member_function.cpp) and '
        'ros2lite runs Python nodes: build and run it with a ROS 2 install (colcon build, '
        'ros2 run), or write the node in Python (ros2lite pkg create --build-type ament_python)\n'
    )
    assert run('run', 'cpp_pubsub', 'talker').err == line
    assert run('pkg', 'executables', 'cpp_pubsub').err == line
    everything = run('pkg', 'executables')  # a C++ package is no failure of the listing
    assert (everything.code, everything.err) == (0, line)
    # the empty C++ package the first lesson makes has nothing to run, as after a build
    write_package(tmp_path / 'src' / 'my_package', 'my_package', build_type='ament_cmake')
    assert run('run', 'my_package', 'x').err == 'No executable found\n'


def test_demo_nodes_cpp_in_every_verb(run: Callable[..., Result]) -> None:
    note = 'demo_nodes_cpp (C++) is not installed; '
    listing = run('pkg', 'executables', 'demo_nodes_cpp')
    assert listing.code == 0
    assert listing.err == (
        f'{note}these run demo_nodes_py, its Python equivalent, and stand-ins bundled with '
        'ros2lite\n'
    )
    names = listing.out.splitlines()
    assert {'demo_nodes_cpp talker', 'demo_nodes_cpp parameter_blackboard'} <= set(names)
    assert names == sorted(names)
    prefix = run('pkg', 'prefix', 'demo_nodes_cpp')
    assert (prefix.out, prefix.err) == (
        f'{BUNDLED_PACKAGES.parent}\n',
        f'{note}this is demo_nodes_py, its Python equivalent\n',
    )
    share = run('pkg', 'prefix', '--share', 'demo_nodes_cpp')
    assert share.out == f'{BUNDLED_PACKAGES}/demo_nodes_py\n'
    xml = run('pkg', 'xml', 'demo_nodes_cpp', '-t', 'name')
    assert (xml.out, xml.err) == (
        'demo_nodes_py\n',
        f'{note}this is demo_nodes_py, its Python equivalent\n',
    )
    cpp_only = run('run', 'demo_nodes_cpp', 'allocator_tutorial')
    assert (cpp_only.code, cpp_only.err) == (
        1,
        "No executable found: demo_nodes_cpp's allocator_tutorial is C++ and ros2lite has no "
        'Python stand-in for it; ros2lite pkg executables demo_nodes_cpp lists what runs\n',
    )
    typo = run('run', 'demo_nodes_cpp', 'talkr')
    assert typo.err == 'No executable found; did you mean: talker, talker_qos?\n'
    missing = run('launch', 'demo_nodes_cpp', 'nope.launch.py')
    assert missing.err == (
        'demo_nodes_cpp (C++) is not installed, and demo_nodes_py, its Python equivalent, has '
        "no launch file 'nope.launch.py'\n"
    )


def test_launch_demo_nodes_cpp_add_two_ints(ros_router: str) -> None:
    """The course's line: the server answers the client once, and the launch ends with it."""
    result = run_process('launch', 'demo_nodes_cpp', 'add_two_ints.launch.py')
    assert result.code == 0, result.out + result.err
    assert (
        '[INFO] [launch]: demo_nodes_cpp (C++) is not installed; launching demo_nodes_py '
        'add_two_ints.launch.py, its Python equivalent'
    ) in result.out
    assert 'Result of add_two_ints: for 2 + 3 = 5' in result.out
