"""`ros2lite launch turtlebot3_gazebo turtlebot3_house.launch.py`: TurtleBot3
($TURTLEBOT3_MODEL, burger by default) in the turtlebot3_house, on ros2lite's 2D simulator; the
description published by robot_state_publisher when that package is installed, by the
simulator otherwise; the top view window with a display unless gui:=false or
headless:=true."""

from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch.substitutions import EnvironmentVariable, LaunchConfiguration
from launch_ros.actions import Node

WORLD = 'turtlebot3_house'


def _robot_state_publisher():
    try:
        from ament_index_python.packages import get_package_share_directory

        get_package_share_directory('robot_state_publisher')
    except Exception:
        return None
    import os

    from ros2lite.sim.robots import robot, urdf

    spec = robot(os.environ.get('TURTLEBOT3_MODEL', 'burger') or 'burger')
    return Node(
        package='robot_state_publisher',
        executable='robot_state_publisher',
        name='robot_state_publisher',
        output='screen',
        parameters=[{'use_sim_time': True, 'robot_description': urdf(spec)}],
    )


def generate_launch_description():
    state_publisher = _robot_state_publisher()
    simulator = Node(
        package='turtlebot3_gazebo',
        executable='gazebo_2d',
        name='gazebo',
        output='screen',
        parameters=[
            {
                'robot_model': EnvironmentVariable('TURTLEBOT3_MODEL', default_value='burger'),
                'world': LaunchConfiguration('world'),
                'x_pose': LaunchConfiguration('x_pose'),
                'y_pose': LaunchConfiguration('y_pose'),
                'real_time_factor': LaunchConfiguration('real_time_factor'),
                'publish_robot_state': state_publisher is None,
                'use_sim_time': True,
            }
        ],
    )
    actions = [
        DeclareLaunchArgument('use_sim_time', default_value='true'),
        DeclareLaunchArgument('world', default_value=WORLD),
        DeclareLaunchArgument('x_pose', default_value='-2.0' if WORLD != 'empty_world' else '0.0'),
        DeclareLaunchArgument('y_pose', default_value='-0.5' if WORLD != 'empty_world' else '0.0'),
        DeclareLaunchArgument('real_time_factor', default_value='1.0'),
        simulator,
    ]
    if state_publisher is not None:
        actions.append(state_publisher)
    from ros2lite.bundled.simulator import view_actions

    return LaunchDescription(actions + view_actions())
