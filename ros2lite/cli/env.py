"""`ros2lite env [--shell bash|zsh|fish]`: the lines that make this shell a ROS shell.

    eval "$(ros2lite env)"            # bash, zsh
    ros2lite env --shell fish | source

The counterpart of sourcing ROS's setup script: afterwards ``python3 my_node.py`` finds
``rclpy`` and every interface package ros2lite knows (see :mod:`ros2lite.pkg.environment`).
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
def cli(shell: str) -> None:
    """Print shell lines that let code written for rclpy run on ros2lite."""
    from ros2lite.pkg.environment import shell_lines

    click.echo(shell_lines(shell), nl=False)
