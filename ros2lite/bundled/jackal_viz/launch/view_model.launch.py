"""`ros2lite launch jackal_viz view_model.launch.py`: rviz2 (ros2lite's browser view) on the
Jackal, its fixed frame `odom`, as Clearpath's launch file opens RViz on the robot model.
`port:=` and `host:=` say where the page is served (rviz2's defaults: 127.0.0.1:8080)."""

from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node


def generate_launch_description():
    return LaunchDescription(
        [
            DeclareLaunchArgument('use_sim_time', default_value='true'),
            DeclareLaunchArgument(
                'host',
                default_value='127.0.0.1',
                description='address the viewer serves on (0.0.0.0 shares it)',
            ),
            DeclareLaunchArgument(
                'port', default_value='8080', description='port the viewer serves on'
            ),
            Node(
                package='rviz2',
                executable='rviz2',
                name='rviz2',
                output='screen',
                arguments=[
                    '--fixed-frame',
                    'odom',
                    '--host',
                    LaunchConfiguration('host'),
                    '--port',
                    LaunchConfiguration('port'),
                ],
                parameters=[{'use_sim_time': LaunchConfiguration('use_sim_time')}],
            ),
        ]
    )
