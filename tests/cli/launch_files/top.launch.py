# The lesson's launch file, Python flavour: a namespace for everything, a talker with a
# remap, a parameter board (a dict and a file), and an included listener given an argument.
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument, GroupAction, IncludeLaunchDescription
from launch.launch_description_sources import PythonLaunchDescriptionSource
from launch.substitutions import LaunchConfiguration, PathJoinSubstitution
from launch_ros.actions import Node, PushRosNamespace
from launch_ros.substitutions import FindPackageShare


def generate_launch_description():
    share = FindPackageShare('lesson_bringup')
    return LaunchDescription(
        [
            DeclareLaunchArgument('ns', default_value='lesson', description='namespace'),
            DeclareLaunchArgument('topic', default_value='words', description='topic to use'),
            GroupAction(
                [
                    PushRosNamespace(LaunchConfiguration('ns')),
                    Node(
                        package='demo_nodes_py',
                        executable='talker',
                        name='speaker',
                        remappings=[('chatter', LaunchConfiguration('topic'))],
                        output='screen',
                    ),
                    Node(
                        package='demo_nodes_cpp',
                        executable='parameter_blackboard',
                        name='board',
                        parameters=[
                            {'answer': 42},
                            PathJoinSubstitution([share, 'config', 'board.yaml']),
                        ],
                    ),
                    IncludeLaunchDescription(
                        PythonLaunchDescriptionSource(
                            PathJoinSubstitution([share, 'launch', 'listen.launch.py'])
                        ),
                        launch_arguments={'heard_topic': LaunchConfiguration('topic')}.items(),
                    ),
                ]
            ),
        ]
    )
