"""The demo packages bundled with ros2lite, and what each can run.

Both the package index (which lists them as packages of its last source) and the executables
(which start them) read this table, so it stands below both.
"""

from __future__ import annotations

__all__ = ['BUNDLED', 'STAND_INS']

# package -> executables, each `main()` of ros2lite.bundled.<package>.<executable> (a name
# with `.py`, as ROS packages install some scripts, is the module without the suffix)
_DEMOS = {
    'action_tutorials_py': ['fibonacci_action_client', 'fibonacci_action_server'],
    # Jazzy's demo_nodes_py (0.33.x), exactly
    'demo_nodes_py': [
        'add_two_ints_client',
        'add_two_ints_client_async',
        'add_two_ints_server',
        'async_param_client',
        'introspection',
        'listener',
        'listener_qos',
        'listener_serialized',
        'matched_event_detect',
        'set_parameters_callback',
        'talker',
        'talker_qos',
        'use_logger_service',
    ],
    'foxglove_bridge': ['foxglove_bridge'],
    'gazebo_ros': ['spawn_entity.py'],
    'jackal_gazebo': ['gazebo_2d'],
    'jackal_viz': [],  # launch files only: view_model.launch.py opens rviz2
    'joint_state_publisher': ['joint_state_publisher'],
    'joint_state_publisher_gui': ['joint_state_publisher_gui'],
    'lifecycle': ['lifecycle_listener'],
    'lifecycle_py': ['lifecycle_talker'],
    'rclpy_components': ['component_container', 'component_container_mt'],
    'robot_state_publisher': ['robot_state_publisher'],
    'ros_gz_sim': ['create'],
    'rqt_console': ['rqt_console'],
    'rqt_graph': ['rqt_graph'],
    'rqt_plot': ['rqt_plot'],
    'rqt_tf_tree': ['rqt_tf_tree'],
    'rviz2': ['rviz2'],
    'teleop_twist_keyboard': ['teleop_twist_keyboard'],
    'tf2_tools': ['view_frames'],
    'tf2_ros': ['static_transform_publisher', 'tf2_echo', 'tf2_monitor'],
    'turtle_tf2_py': [
        'dynamic_frame_tf2_broadcaster',
        'fixed_frame_tf2_broadcaster',
        'static_turtle_tf2_broadcaster',
        'turtle_tf2_broadcaster',
        'turtle_tf2_listener',
    ],
    'tiago_gazebo': ['gazebo_2d'],
    'turtlebot3_gazebo': ['gazebo_2d'],
    'turtlesim': ['draw_square', 'mimic', 'turtle_teleop_key', 'turtlesim_node'],
    'urdf_launch': [],  # launch files only
    'xacro': ['xacro'],
}


def _target(package: str, name: str) -> str:
    return f'ros2lite.bundled.{package}.{name.removesuffix(".py")}:main'


BUNDLED: dict[str, dict[str, str]] = {
    package: {name: _target(package, name) for name in names} for package, names in _DEMOS.items()
}
"""Bundled demo package -> executable name -> its `module:function` target."""

# executables that only the C++ twin of a bundled package has (demo_nodes_cpp's, next to the
# demo_nodes_py ones of the same name): modules of the bundled package, run only as that twin's
# stand-in, so the package's own list stays the real one
_STAND_INS = {
    'demo_nodes_py': ['introspection_client', 'introspection_service', 'parameter_blackboard']
}
STAND_INS: dict[str, dict[str, str]] = {
    package: {name: _target(package, name) for name in names}
    for package, names in _STAND_INS.items()
}
"""Bundled package -> executable its C++ twin has and it does not -> `module:function`."""
