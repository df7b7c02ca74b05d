"""Two turtlesim windows, each under its own namespace (`ros2lite launch turtlesim
multisim.launch.py`, as in the ROS tutorials)."""

from launch import LaunchDescription
from launch_ros.actions import Node


def generate_launch_description():
    return LaunchDescription(
        [
            Node(
                namespace='turtlesim1',
                package='turtlesim',
                executable='turtlesim_node',
                output='screen',
            ),
            Node(
                namespace='turtlesim2',
                package='turtlesim',
                executable='turtlesim_node',
                output='screen',
            ),
        ]
    )
