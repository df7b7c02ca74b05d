"""Show a package's robot: description.launch.py (robot_state_publisher), the joint state
publisher (its GUI's sliders with `jsp_gui:=true`, the default) and rviz2 with `rviz_config`.

Arguments: `urdf_package`, `urdf_package_path` (as description.launch.py), `jsp_gui`,
`rviz_config`, `use_sim_time`, and `rviz` (default true; false leaves the viewer out, e.g.
on a machine without a browser)."""

from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument, IncludeLaunchDescription
from launch.conditions import IfCondition, UnlessCondition
from launch.substitutions import LaunchConfiguration, PathJoinSubstitution
from launch_ros.actions import Node, SetParameter
from launch_ros.substitutions import FindPackageShare


def generate_launch_description():
    share = FindPackageShare('urdf_launch')
    return LaunchDescription(
        [
            DeclareLaunchArgument(
                'jsp_gui',
                default_value='true',
                choices=['true', 'false'],
                description='Run joint_state_publisher_gui (true) or joint_state_publisher',
            ),
            DeclareLaunchArgument(
                'rviz_config',
                default_value=PathJoinSubstitution([share, 'config', 'urdf.rviz']),
                description="The viewer's configuration file",
            ),
            DeclareLaunchArgument(
                'use_sim_time',
                default_value='false',
                choices=['true', 'false'],
                description='Follow /clock (a simulator) rather than the wall clock',
            ),
            DeclareLaunchArgument(
                'rviz', default_value='true', choices=['true', 'false'], description='Run rviz2'
            ),
            SetParameter(name='use_sim_time', value=LaunchConfiguration('use_sim_time')),
            IncludeLaunchDescription(
                PathJoinSubstitution([share, 'launch', 'description.launch.py']),
                launch_arguments={
                    'urdf_package': LaunchConfiguration('urdf_package'),
                    'urdf_package_path': LaunchConfiguration('urdf_package_path'),
                }.items(),
            ),
            Node(
                package='joint_state_publisher',
                executable='joint_state_publisher',
                condition=UnlessCondition(LaunchConfiguration('jsp_gui')),
            ),
            Node(
                package='joint_state_publisher_gui',
                executable='joint_state_publisher_gui',
                condition=IfCondition(LaunchConfiguration('jsp_gui')),
            ),
            Node(
                package='rviz2',
                executable='rviz2',
                output='screen',
                arguments=['-d', LaunchConfiguration('rviz_config')],
                condition=IfCondition(LaunchConfiguration('rviz')),
            ),
        ]
    )
