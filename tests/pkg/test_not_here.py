"""The one table of what ros2lite does not provide, and what each row tells the user."""

from __future__ import annotations

from pathlib import Path

from ros2lite.pkg.bundled import BUNDLED
from ros2lite.pkg.executables import EQUIVALENTS
from ros2lite.pkg.not_here import (
    NOT_HERE,
    cpp_executable_line,
    cpp_package_line,
    cpp_sources,
    not_here_line,
)


def test_no_row_names_a_package_ros2lite_has() -> None:
    assert not set(NOT_HERE) & (set(BUNDLED) | set(EQUIVALENTS))


def test_each_line_says_what_is_missing_and_what_to_use() -> None:
    assert not_here_line('gazebo_plugins') == (
        "gazebo_plugins belongs to Gazebo, a 3D simulator ros2lite does not run; ros2lite's 2D "
        "simulator stands in for the courses' robots (ros2lite launch turtlebot3_gazebo "
        'empty_world.launch.py) and spawns a URDF robot (ros2lite run gazebo_ros spawn_entity.py)'
    )
    assert not_here_line('rviz_default_plugins') == (
        "rviz_default_plugins belongs to rviz's C++ plugins, which ros2lite does not load; "
        "ros2lite's rviz2 shows the scene in a browser (ros2lite run rviz2 rviz2), or run the "
        'Foxglove bridge (ros2lite run foxglove_bridge foxglove_bridge) and open '
        'ws://localhost:8765 in Foxglove'
    )
    assert not_here_line('rviz2') is None  # bundled: the browser view
    assert not_here_line('image_tools') == (
        'image_tools is a C++ package, and ros2lite runs Python nodes; run it from a ROS 2 '
        'install, or use a Python package that does the same'
    )
    assert not_here_line('my_own_package') is None
    for row in NOT_HERE:
        line = not_here_line(row)
        assert line is not None and line.startswith(row) and 'ros2lite' in line


def test_cpp_executables_without_a_stand_in() -> None:
    assert cpp_executable_line('demo_nodes_cpp', 'allocator_tutorial') == (
        "No executable found: demo_nodes_cpp's allocator_tutorial is C++ and ros2lite has no "
        'Python stand-in for it; ros2lite pkg executables demo_nodes_cpp lists what runs'
    )
    assert cpp_executable_line('demo_nodes_cpp', 'no_such_thing') is None


def test_cpp_sources_of_a_package(tmp_path: Path) -> None:
    (tmp_path / 'src').mkdir()
    (tmp_path / 'src' / 'node.cpp').write_text('int main() {}\n')
    (tmp_path / 'src' / 'util.cc').write_text('\n')
    (tmp_path / '.git').mkdir()
    (tmp_path / '.git' / 'x.cpp').write_text('\n')
    (tmp_path / 'CMakeLists.txt').write_text('\n')
    sources = cpp_sources(tmp_path)
    assert sources == [tmp_path / 'src' / 'node.cpp', tmp_path / 'src' / 'util.cc']
    assert cpp_package_line('my_cpp', tmp_path, sources).startswith(
        'my_cpp is a C++ package (ament_cmake, src/node.cpp …) and ros2lite runs Python nodes'
    )
    assert cpp_sources(tmp_path / 'src' / 'node.cpp') == []
