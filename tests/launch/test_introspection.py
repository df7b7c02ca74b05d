"""`launch -s` and `launch -p` texts."""

from __future__ import annotations

from pathlib import Path

from ros2lite.launch.actions import DeclareLaunchArgument, LaunchDescription
from ros2lite.launch.conditions import IfCondition
from ros2lite.launch.flow import GroupAction, IncludeLaunchDescription, LogInfo, TimerAction
from ros2lite.launch.introspection import describe_tree, format_arguments
from ros2lite.launch.sources import PythonLaunchDescriptionSource
from ros2lite.launch.substitutions import LaunchConfiguration


def test_arguments_of_a_description_and_its_includes(tmp_path: Path) -> None:
    child = tmp_path / 'child.launch.py'
    child.write_text(
        'from launch import LaunchDescription\n'
        'from launch.actions import DeclareLaunchArgument\n'
        'def generate_launch_description():\n'
        "    return LaunchDescription([DeclareLaunchArgument('from_child', default_value='1')])\n"
    )
    description = LaunchDescription(
        [
            DeclareLaunchArgument('use_sim_time', default_value='false', description='Sim time?'),
            DeclareLaunchArgument('mode', choices=['a', 'b'], default_value='a'),
            GroupAction([DeclareLaunchArgument('only_if')], condition=IfCondition('true')),
            TimerAction(
                period=1.0,
                actions=[
                    DeclareLaunchArgument('later', default_value=['x', LaunchConfiguration('mode')])
                ],
            ),
            IncludeLaunchDescription(PythonLaunchDescriptionSource(str(child))),
        ]
    )
    assert format_arguments(description) == (
        "Arguments (pass arguments as '<name>:=<value>'):\n"
        "\n    'use_sim_time':\n        Sim time?\n        (default: 'false')\n"
        "\n    'mode':\n        no description given\n        Valid choices are: ['a', 'b']\n"
        "        (default: 'a')\n"
        "\n    'only_if'*:\n        no description given\n"
        "\n    'later'*:\n        no description given\n"
        "        (default: 'x' + LaunchConfig('mode'))\n"
        "\n    'from_child':\n        no description given\n        (default: '1')\n"
        '\n* argument(s) which are only used if specific conditions occur'
    )
    assert format_arguments(LaunchDescription([])).endswith('\n\n  No arguments.')


def test_tree() -> None:
    description = LaunchDescription(
        [
            GroupAction([LogInfo(msg='a')], condition=IfCondition('true')),
            LogInfo(msg='b'),
        ]
    )
    assert describe_tree(description) == (
        'LaunchDescription\n'
        "├── GroupAction(scoped=True) [IfCondition('true')]\n"
        "│   └── LogInfo('a')\n"
        "└── LogInfo('b')"
    )
