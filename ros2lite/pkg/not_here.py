"""What ros2lite does not provide, and what to use instead: one table, a row per package.

Courses type lines for C++ nodes, Gazebo and rviz2. ros2lite runs Python nodes and bundles
Python stand-ins for some C++ demos (:data:`ros2lite.pkg.executables.EQUIVALENTS`); for the
rest, every lookup that fails (`run`, `launch`, `pkg`, `interface`, a launch file's
`FindPackageShare`) ends in the one line this table gives. A package ros2lite bundles has
no row (the 2D simulator's and the browser viewer's packages answer for themselves).
"""

from __future__ import annotations

from pathlib import Path

__all__ = [
    'CPP_SOURCE_SUFFIXES',
    'NOT_HERE',
    'cpp_executable_line',
    'cpp_package_line',
    'cpp_sources',
    'not_here_line',
]

_SIMULATOR = (
    '{package} belongs to Gazebo, a 3D simulator ros2lite does not run; ros2lite\'s 2D '
    'simulator stands in for the courses\' robots (ros2lite launch turtlebot3_gazebo '
    'empty_world.launch.py) and spawns a URDF robot (ros2lite run gazebo_ros spawn_entity.py)'
)
_VIEWER = (
    '{package} belongs to rviz\'s C++ plugins, which ros2lite does not load; ros2lite\'s rviz2 '
    'shows the scene in a browser (ros2lite run rviz2 rviz2), or run the Foxglove bridge '
    '(ros2lite run foxglove_bridge foxglove_bridge) and open ws://localhost:8765 in Foxglove'
)
_CPP = (
    '{package} is a C++ package, and ros2lite runs Python nodes; run it from a ROS 2 '
    'install, or use a Python package that does the same'
)

# package -> why it is not here and what to use instead ({package}: its name)
NOT_HERE: dict[str, str] = {
    **dict.fromkeys(
        (
            'gazebo',
            'gazebo_ros_pkgs',
            'gazebo_plugins',
            'gazebo_msgs',
            'gz_ros2_control',
            'ros_gz',
            'ros_gz_bridge',
            'ros_gz_image',
            'ros_gz_interfaces',
            'ros_ign_gazebo',
            'ros_ign_bridge',
            'turtlebot3_simulations',
        ),
        _SIMULATOR,
    ),
    **dict.fromkeys(('rviz', 'rviz_common', 'rviz_default_plugins'), _VIEWER),
    **dict.fromkeys(
        (
            'action_tutorials_cpp',
            'demo_nodes_cpp_native',
            'dummy_map_server',
            'dummy_robot_bringup',
            'dummy_sensors',
            'examples_rclcpp_minimal_action_client',
            'examples_rclcpp_minimal_action_server',
            'examples_rclcpp_minimal_client',
            'examples_rclcpp_minimal_composition',
            'examples_rclcpp_minimal_publisher',
            'examples_rclcpp_minimal_service',
            'examples_rclcpp_minimal_subscriber',
            'examples_rclcpp_minimal_timer',
            'examples_rclcpp_multithreaded_executor',
            'image_tools',
            'intra_process_demo',
            'joy',
            'logging_demo',
            'pendulum_control',
            'quality_of_service_demo_cpp',
            'teleop_twist_joy',
        ),
        _CPP,
    ),
    'rclcpp_components': (
        '{package} is C++ (it loads C++ components), and ros2lite runs Python nodes; '
        'ros2lite\'s container loads Python components: '
        'ros2lite run rclpy_components component_container'
    ),
}


def not_here_line(package: str) -> str | None:
    """Why `package` is not here and what to use instead, or None when the table has no row."""
    row = NOT_HERE.get(package)
    return row.format(package=package) if row is not None else None


# Jazzy demo_nodes_cpp's executables; those without a Python twin or stand-in get a line
_DEMO_NODES_CPP = frozenset(
    {
        'add_two_ints_client',
        'add_two_ints_client_async',
        'add_two_ints_server',
        'allocator_tutorial',
        'content_filtering_publisher',
        'content_filtering_subscriber',
        'even_parameters_node',
        'introspection_client',
        'introspection_service',
        'list_parameters',
        'list_parameters_async',
        'listener',
        'listener_best_effort',
        'listener_serialized_message',
        'matched_event_detect',
        'one_off_timer',
        'parameter_blackboard',
        'parameter_event_handler',
        'parameter_events',
        'parameter_events_async',
        'reuse_timer',
        'set_and_get_parameters',
        'set_and_get_parameters_async',
        'talker',
        'talker_loaned_message',
        'talker_serialized_message',
    }
)
_CPP_EXECUTABLES = {'demo_nodes_cpp': _DEMO_NODES_CPP}


def cpp_executable_line(package: str, executable: str) -> str | None:
    """The line for a C++ package's executable that no Python stand-in replaces (asked only
    once the stand-ins had no answer), or None when it is no such executable."""
    if executable not in _CPP_EXECUTABLES.get(package, ()):
        return None
    return (
        f"No executable found: {package}'s {executable} is C++ and ros2lite has no Python "
        f'stand-in for it; ros2lite pkg executables {package} lists what runs'
    )


CPP_SOURCE_SUFFIXES = ('.cpp', '.cc', '.cxx', '.c++', '.c')
_MAX_LOOKED_AT = 500


def cpp_sources(directory: Path) -> list[Path]:
    """C/C++ source files of a source package (a bounded look, skipping hidden folders)."""
    found: list[Path] = []
    looked = 0
    stack = [directory]
    while stack and looked < _MAX_LOOKED_AT:
        current = stack.pop()
        try:
            entries = sorted(current.iterdir())
        except OSError:
            continue
        for entry in entries:
            looked += 1
            if entry.name.startswith('.'):
                continue
            if entry.is_dir() and not entry.is_symlink():
                stack.append(entry)
            elif entry.suffix in CPP_SOURCE_SUFFIXES:
                found.append(entry)
    return sorted(found)


def cpp_package_line(package: str, directory: Path, sources: list[Path]) -> str:
    """The line for a workspace's ament_cmake package with C++ sources."""
    first = sources[0].relative_to(directory) if sources else ''
    return (
        f"{package} is a C++ package (ament_cmake, {first}{' …' if len(sources) > 1 else ''}) "
        'and ros2lite runs Python nodes: build and run it with a ROS 2 install (colcon build, '
        'ros2 run), or write the node in Python (ros2lite pkg create --build-type ament_python)'
    )
