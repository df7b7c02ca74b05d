"""The demo packages bundled with ros2lite, and what each can run.

Both the package index (which lists them as packages of its last source) and the executables
(which start them) read this table, so it stands below both.
"""

from __future__ import annotations

__all__ = ['BUNDLED']

# package -> executables, each `main()` of ros2lite.demos.<package>.<executable>
_DEMOS = {
    'action_tutorials_py': ['fibonacci_action_client', 'fibonacci_action_server'],
    'demo_nodes_py': [
        'add_two_ints_client',
        'add_two_ints_client_async',
        'add_two_ints_server',
        'introspection_client',
        'introspection_service',
        'listener',
        'parameter_blackboard',
        'talker',
    ],
    'foxglove_bridge': ['foxglove_bridge'],
    'lifecycle': ['lifecycle_listener'],
    'lifecycle_py': ['lifecycle_talker'],
    'rclpy_components': ['component_container', 'component_container_mt'],
    'rqt_graph': ['rqt_graph'],
    'teleop_twist_keyboard': ['teleop_twist_keyboard'],
    'turtlesim': ['draw_square', 'mimic', 'turtle_teleop_key', 'turtlesim_node'],
}
BUNDLED: dict[str, dict[str, str]] = {
    package: {name: f'ros2lite.demos.{package}.{name}:main' for name in names}
    for package, names in _DEMOS.items()
}
"""Bundled demo package -> executable name -> its `module:function` target."""
