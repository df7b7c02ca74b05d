# Every launch feature a ROS course names, imported by its ROS name: a shell command whose
# exit is an event, conditions, an opaque function, a timer, and a node in a namespace given
# a global parameter, parameters from a dict and a file, and command-line arguments.
from launch import LaunchDescription
from launch.actions import (
    DeclareLaunchArgument,
    ExecuteProcess,
    GroupAction,
    LogInfo,
    OpaqueFunction,
    RegisterEventHandler,
    TimerAction,
)
from launch.conditions import IfCondition, UnlessCondition
from launch.event_handlers import OnProcessExit
from launch.substitutions import (
    EnvironmentVariable,
    LaunchConfiguration,
    PathJoinSubstitution,
    TextSubstitution,
)
from launch_ros.actions import Node, PushRosNamespace, SetParameter
from launch_ros.substitutions import FindPackageShare


def generate_launch_description():
    greet = ExecuteProcess(
        cmd=['echo', [TextSubstitution(text='hello '), EnvironmentVariable('LESSON_WHO')]],
        name='greet',
        output='screen',
    )

    def report(context):
        return [LogInfo(msg='mode is ' + LaunchConfiguration('mode').perform(context))]

    return LaunchDescription(
        [
            DeclareLaunchArgument('mode', default_value='slow', description='how to run'),
            DeclareLaunchArgument('extra', default_value='false', description='one more'),
            RegisterEventHandler(
                OnProcessExit(target_action=greet, on_exit=[LogInfo(msg='greet is done')])
            ),
            greet,
            ExecuteProcess(
                cmd=['echo', 'with extra'],
                output='screen',
                condition=IfCondition(LaunchConfiguration('extra')),
            ),
            ExecuteProcess(
                cmd=['echo', 'without extra'],
                output='screen',
                condition=UnlessCondition(LaunchConfiguration('extra')),
            ),
            OpaqueFunction(function=report),
            GroupAction(
                [
                    PushRosNamespace('feat'),
                    SetParameter(name='answer', value=42),
                    TimerAction(
                        period=0.5,
                        actions=[
                            Node(
                                package='lesson_bringup',
                                executable='show',
                                name='shower',
                                arguments=['--mode', LaunchConfiguration('mode')],
                                parameters=[
                                    {'label': 'from a dict'},
                                    PathJoinSubstitution(
                                        [FindPackageShare('lesson_bringup'), 'config', 'board.yaml']
                                    ),
                                ],
                                output='screen',
                            )
                        ],
                    ),
                ]
            ),
        ]
    )
