"""A package's robot description (xacro or plain URDF, run through xacro either way) given
to robot_state_publisher as its `robot_description` parameter.

Arguments: `urdf_package` (the package holding the file) and `urdf_package_path` (the file,
relative to that package's share folder)."""

from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch.substitutions import Command, LaunchConfiguration, PathJoinSubstitution
from launch_ros.actions import Node
from launch_ros.parameter_descriptions import ParameterValue
from launch_ros.substitutions import FindPackageShare


def generate_launch_description():
    path = PathJoinSubstitution(
        [
            FindPackageShare(LaunchConfiguration('urdf_package')),
            LaunchConfiguration('urdf_package_path'),
        ]
    )
    description = ParameterValue(Command(['xacro ', path]), value_type=str)
    return LaunchDescription(
        [
            DeclareLaunchArgument(
                'urdf_package', description='The package that holds the robot description'
            ),
            DeclareLaunchArgument(
                'urdf_package_path',
                description="The robot description's path, relative to the package's share folder",
            ),
            Node(
                package='robot_state_publisher',
                executable='robot_state_publisher',
                parameters=[{'robot_description': description}],
            ),
        ]
    )
