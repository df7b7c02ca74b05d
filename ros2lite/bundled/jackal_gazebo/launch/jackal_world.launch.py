"""`ros2lite launch jackal_gazebo jackal_world.launch.py`: the Jackal in the race world (or
`world_path:=<a .world file>`), on ros2lite's 2D simulator; the description published by
robot_state_publisher when that package is installed, by the simulator otherwise; the top
view window with a display unless gui:=false or headless:=true."""

from launch.actions import DeclareLaunchArgument
from launch.substitutions import LaunchConfiguration


def generate_launch_description():
    from ros2lite.bundled.simulator import simulator_launch

    return simulator_launch(
        'jackal_gazebo',
        'jackal',
        [
            DeclareLaunchArgument('world_path', default_value='jackal_race'),
            DeclareLaunchArgument('real_time_factor', default_value='1.0'),
        ],
        {
            'world': LaunchConfiguration('world_path'),
            'real_time_factor': LaunchConfiguration('real_time_factor'),
        },
    )
