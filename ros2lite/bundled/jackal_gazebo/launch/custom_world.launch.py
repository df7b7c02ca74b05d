"""`ros2lite launch jackal_gazebo custom_world.launch.py world:=<name>`: the Jackal in a
world the course saved into jackal_gazebo's `worlds/` folder (`<name>` or `<name>.world`),
or any `.world` file or map YAML by path, on ros2lite's 2D simulator."""

import os

from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument, IncludeLaunchDescription, OpaqueFunction
from launch.launch_description_sources import PythonLaunchDescriptionSource
from launch.substitutions import LaunchConfiguration

HERE = os.path.dirname(os.path.abspath(__file__))


def _world_file(name):
    """The world file `name` names: a path as given, else one in this package's worlds/."""
    if os.path.isfile(name):
        return name
    from ament_index_python.packages import get_package_share_directory

    worlds = os.path.join(get_package_share_directory('jackal_gazebo'), 'worlds')
    for candidate in (name, name + '.world', name + '.sdf'):
        path = os.path.join(worlds, candidate)
        if os.path.isfile(path):
            return path
    return name  # a bundled world's name, or the simulator says it does not exist


def _include(context):
    world = _world_file(LaunchConfiguration('world').perform(context))
    return [
        IncludeLaunchDescription(
            PythonLaunchDescriptionSource(os.path.join(HERE, 'jackal_world.launch.py')),
            launch_arguments={
                'world_path': world,
                'real_time_factor': LaunchConfiguration('real_time_factor'),
            }.items(),
        )
    ]


def generate_launch_description():
    return LaunchDescription(
        [
            DeclareLaunchArgument('world', default_value='jackal_race'),
            DeclareLaunchArgument('real_time_factor', default_value='1.0'),
            OpaqueFunction(function=_include),
        ]
    )
