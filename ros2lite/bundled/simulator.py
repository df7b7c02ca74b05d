"""The body of every simulator executable (`turtlebot3_gazebo gazebo_2d`, `jackal_gazebo
gazebo_2d`, ...): ros2lite's 2D simulator node for a default robot, spun until Ctrl-C; and
what the simulator packages' launch files share: the simulator node with its description's
publisher, and the views."""

from __future__ import annotations

from typing import TYPE_CHECKING

from ros2lite.bundled.runner import run_main

if TYPE_CHECKING:
    from ros2lite.launch.actions import LaunchDescription
    from ros2lite.launch.entity import LaunchDescriptionEntity
    from ros2lite.launch.ros import Node


def run_simulator(default_model: str, args: list[str] | None = None) -> int:
    """Run the simulator with `default_model` unless the `robot_model` parameter says else."""

    def body() -> None:
        import ros2lite
        from ros2lite.sim.node import Settings, SimNode

        node = SimNode(Settings(robot_model=default_model))
        try:
            ros2lite.spin(node)
        finally:
            node.destroy_node()

    return run_main(body, args)


def simulator_launch(
    package: str,
    model: str,
    arguments: list[LaunchDescriptionEntity],
    parameters: dict[str, object],
    *,
    state_publisher_name: str | None = None,
) -> LaunchDescription:
    """A simulator launch file's description: its `arguments`, `package`'s `gazebo_2d` as
    `/gazebo` with `parameters` (and sim time), robot_state_publisher with robot `model`'s
    description when that package is installed (else the simulator publishes it), the views."""
    from ros2lite.launch.actions import LaunchDescription
    from ros2lite.launch.ros import Node

    state_publisher = robot_state_publisher(model, name=state_publisher_name)
    simulator_parameters: dict[str, object] = {
        **parameters,
        'publish_robot_state': state_publisher is None,
        'use_sim_time': True,
    }
    simulator = Node(
        package=package,
        executable='gazebo_2d',
        name='gazebo',
        output='screen',
        parameters=[simulator_parameters],
    )
    actions = [*arguments, simulator]
    if state_publisher is not None:
        actions.append(state_publisher)
    return LaunchDescription(actions + view_actions())


def robot_state_publisher(model: str, *, name: str | None = None) -> Node | None:
    """robot_state_publisher with robot `model`'s description, on sim time, when that package
    is installed; None when it is not."""
    try:
        from ament_index_python.packages import get_package_share_directory

        get_package_share_directory('robot_state_publisher')
    except Exception:
        return None
    from ros2lite.launch.ros import Node
    from ros2lite.sim.robots import robot, urdf

    return Node(
        package='robot_state_publisher',
        executable='robot_state_publisher',
        name=name,
        output='screen',
        parameters=[{'use_sim_time': True, 'robot_description': urdf(robot(model))}],
    )


def view_actions() -> list[LaunchDescriptionEntity]:
    """The launch files' views, as Gazebo's client: `gui:=true` (the default) opens the top
    view window (`ros2lite.bundled.rviz2.top_window`) when there is a display, `gui:=false`
    or `headless:=true` opens none. Over SSH, `python -m ros2lite.bundled.rviz2.top_view`
    draws the same scene in the terminal."""
    import os
    import sys

    from ros2lite.launch.actions import DeclareLaunchArgument
    from ros2lite.launch.conditions import IfCondition
    from ros2lite.launch.execute import ExecuteProcess
    from ros2lite.launch.flow import LogInfo
    from ros2lite.launch.substitutions import (
        AndSubstitution,
        LaunchConfiguration,
        NotSubstitution,
    )

    actions: list[LaunchDescriptionEntity] = [
        DeclareLaunchArgument('gui', default_value='true', description='open the top view window'),
        DeclareLaunchArgument('headless', default_value='false', description='no window at all'),
    ]
    if not (os.environ.get('DISPLAY') or os.environ.get('WAYLAND_DISPLAY')):
        terminal = f'{sys.executable} -m ros2lite.bundled.rviz2.top_view'
        actions.append(LogInfo(msg=f'no display for the window; the terminal view: {terminal}'))
        return actions
    show = AndSubstitution(
        LaunchConfiguration('gui'), NotSubstitution(LaunchConfiguration('headless'))
    )
    actions.append(
        ExecuteProcess(
            cmd=[sys.executable, '-m', 'ros2lite.bundled.rviz2.top_window', '--no-frames'],
            name='top_window',
            output='screen',
            condition=IfCondition(show),
        )
    )
    return actions
