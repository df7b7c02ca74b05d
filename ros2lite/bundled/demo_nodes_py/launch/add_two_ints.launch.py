"""The add_two_ints server and a client asking it once; the launch ends when the client has
its answer (the course's `launch demo_nodes_cpp add_two_ints.launch.py`, in Python)."""

from launch import LaunchDescription
from launch.actions import Shutdown
from launch_ros.actions import Node


def generate_launch_description():
    return LaunchDescription(
        [
            Node(package='demo_nodes_py', executable='add_two_ints_server', output='screen'),
            Node(
                package='demo_nodes_py',
                executable='add_two_ints_client',
                output='screen',
                on_exit=Shutdown(),
            ),
        ]
    )
