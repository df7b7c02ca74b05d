"""`ros2lite env [--shell bash|zsh|fish] [--ros2|--no-ros2]`: the lines that make this shell a
ROS shell.

    eval "$(ros2lite env)"            # bash, zsh
    ros2lite env --shell fish | source

The counterpart of sourcing ROS's setup script: afterwards ``python3 my_node.py`` finds
``rclpy`` and every interface package ros2lite knows (see :mod:`ros2lite.pkg.environment`),
the workspace it was run in stays found from any directory, ``ros2 topic list`` runs ros2lite
with tab completion (unless a real ``ros2`` is on PATH), and ``rosdep``/``vcs`` say what to do
instead when they are not installed (see :mod:`ros2lite.pkg.shell`).
"""

from __future__ import annotations

import click

from .parsing import command


@command('env')
@click.option(
    '--shell',
    type=click.Choice(['bash', 'zsh', 'fish']),
    default='bash',
    show_default=True,
    help='Shell to write the lines for.',
)
@click.option(
    '--ros2/--no-ros2',
    'ros2',
    default=None,
    help='Define `ros2` as ros2lite even if a ROS 2 `ros2` is on PATH (--ros2), or never '
    '(--no-ros2). Default: only when none is.',
)
def cli(shell: str, ros2: bool | None) -> None:
    """Print shell lines that make this shell a ROS shell.

    Use as eval "$(ros2lite env)": code written for rclpy runs on ros2lite, `ros2` runs
    ros2lite with Tab completion, and the workspace this runs in is found from anywhere.
    """
    from ros2lite.pkg.environment import shell_lines
    from ros2lite.pkg.shell import command_lines
    from ros2lite.pkg.workspace import workspaces

    from .main import COMPLETE_VAR

    click.echo(shell_lines(shell, workspaces=workspaces()), nl=False)
    click.echo(command_lines(shell, complete_var=COMPLETE_VAR, ros2=ros2), nl=False)
