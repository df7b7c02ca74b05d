"""`ros2lite launch jackal_gazebo jackal_world.launch.py`: the Jackal in the race world (or
`world_path:=<a .world file>`), on ros2lite's 2D simulator; the description published by
robot_state_publisher when that package is installed, by the simulator otherwise; the top
view window with a display unless gui:=false or headless:=true."""

from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node


def _robot_state_publisher():
    try:
        from ament_index_python.packages import get_package_share_directory

        get_package_share_directory('robot_state_publisher')
    except Exception:
        return None
    from ros2lite.sim.robots import robot, urdf

    return Node(
        package='robot_state_publisher',
        executable='robot_state_publisher',
        output='screen',
        parameters=[{'use_sim_time': True, 'robot_description': urdf(robot('jackal'))}],
    )


def generate_launch_description():
    state_publisher = _robot_state_publisher()
    simulator = Node(
        package='jackal_gazebo',
        executable='gazebo_2d',
        name='gazebo',
        output='screen',
        parameters=[
            {
                'world': LaunchConfiguration('world_path'),
                'real_time_factor': LaunchConfiguration('real_time_factor'),
                'publish_robot_state': state_publisher is None,
                'use_sim_time': True,
            }
        ],
    )
    actions = [
        DeclareLaunchArgument('world_path', default_value='jackal_race'),
        DeclareLaunchArgument('real_time_factor', default_value='1.0'),
        simulator,
    ]
    if state_publisher is not None:
        actions.append(state_publisher)
    from ros2lite.bundled.simulator import view_actions

    return LaunchDescription(actions + view_actions())
