"""`ros2lite extension_points`: the extension points, in ros2cli's format.

ros2lite's commands and verbs are tables, not entry points; they are listed under the group
names ros2cli would use (`ros2cli.command`, `ros2<command>.verb`), so a script reading
ros2cli's output reads ours.
"""

from __future__ import annotations

import click

from . import parsing


@parsing.command('extension_points')
@click.option(
    '-a',
    '--all',
    'show_all',
    is_flag=True,
    help='Also show extension points which failed to be imported (none can here)',
)
@click.option(
    '-v', '--verbose', is_flag=True, help='Show more information for each extension point'
)
def cli(show_all: bool, verbose: bool) -> None:
    """List extension points."""
    from .main import verb_tables

    points = {'ros2cli.command': ("'command' extensions", 'ros2lite.cli.main', 'COMMANDS')}
    for group, (command, _verbs) in verb_tables().items():
        points[group] = (f"'{command}' verb extensions", f'ros2lite.cli.{command}', 'VERBS')
    for name in sorted(points):
        what, module, attribute = points[name]
        click.echo(f'{name}: The extension point for {what}')
        if verbose:
            click.echo(f'    module_name: {module}')
            click.echo(f'    attributes: {attribute}')
            click.echo('    version: 0.1')
