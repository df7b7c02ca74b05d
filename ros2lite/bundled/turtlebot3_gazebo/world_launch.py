"""What turtlebot3_gazebo's three world launch files build (empty_world, turtlebot3_world,
turtlebot3_house): they differ only in the world, so each names its world and this module
holds the rest once, as upstream's three files are one pattern too."""

from __future__ import annotations

import os
from typing import TYPE_CHECKING

from ros2lite.bundled.simulator import simulator_launch
from ros2lite.launch.actions import DeclareLaunchArgument
from ros2lite.launch.substitutions import EnvironmentVariable, LaunchConfiguration

if TYPE_CHECKING:
    from ros2lite.launch.actions import LaunchDescription

__all__ = ['world_launch']


def world_launch(world: str) -> LaunchDescription:
    """TurtleBot3 ($TURTLEBOT3_MODEL, burger by default) in `world` on the 2D simulator, at
    the world's usual spawn point (the origin in the empty world); the launch arguments
    world, x_pose, y_pose and real_time_factor change that."""
    away = world != 'empty_world'
    return simulator_launch(
        'turtlebot3_gazebo',
        os.environ.get('TURTLEBOT3_MODEL', 'burger') or 'burger',
        [
            DeclareLaunchArgument('use_sim_time', default_value='true'),
            DeclareLaunchArgument('world', default_value=world),
            DeclareLaunchArgument('x_pose', default_value='-2.0' if away else '0.0'),
            DeclareLaunchArgument('y_pose', default_value='-0.5' if away else '0.0'),
            DeclareLaunchArgument('real_time_factor', default_value='1.0'),
        ],
        {
            'robot_model': EnvironmentVariable('TURTLEBOT3_MODEL', default_value='burger'),
            'world': LaunchConfiguration('world'),
            'x_pose': LaunchConfiguration('x_pose'),
            'y_pose': LaunchConfiguration('y_pose'),
            'real_time_factor': LaunchConfiguration('real_time_factor'),
        },
        state_publisher_name='robot_state_publisher',
    )
