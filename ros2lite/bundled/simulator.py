"""The body of every simulator executable (`turtlebot3_gazebo gazebo_2d`, `jackal_gazebo
gazebo_2d`, ...): ros2lite's 2D simulator node for a default robot, spun until Ctrl-C."""

from __future__ import annotations

from ros2lite.bundled.runner import run_main


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


def view_actions() -> list[object]:
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

    actions: list[object] = [
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
