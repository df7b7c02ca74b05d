"""`ros2lite launch jackal_viz view_model.launch.py`: rviz2 (ros2lite's browser view) on the
Jackal, its fixed frame `odom`, as Clearpath's launch file opens RViz on the robot model."""

from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node


def generate_launch_description():
    return LaunchDescription(
        [
            DeclareLaunchArgument('use_sim_time', default_value='true'),
            Node(
                package='rviz2',
                executable='rviz2',
                name='rviz2',
                output='screen',
                arguments=['--fixed-frame', 'odom'],
                parameters=[{'use_sim_time': LaunchConfiguration('use_sim_time')}],
            ),
        ]
    )
