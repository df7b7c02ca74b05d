from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node


def generate_launch_description():
    return LaunchDescription(
        [
            DeclareLaunchArgument('heard_topic'),
            Node(
                package='demo_nodes_py',
                executable='listener',
                remappings=[('chatter', LaunchConfiguration('heard_topic'))],
                output='screen',
            ),
        ]
    )
