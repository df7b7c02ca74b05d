"""`ros2lite extensions`: every command and verb, grouped as ros2cli groups its extensions."""

from __future__ import annotations

import click

from .parsing import command


@command('extensions')
@click.option(
    '-a',
    '--all',
    'show_all',
    is_flag=True,
    help='Also show extensions which failed to load or are incompatible (none can here)',
)
@click.option('-v', '--verbose', is_flag=True, help='Show more information for each extension')
def cli(show_all: bool, verbose: bool) -> None:
    """List extensions."""
    from importlib.metadata import PackageNotFoundError, version

    from .main import COMMANDS, verb_tables

    try:
        distribution = f'ros2lite {version("ros2lite")}'
    except PackageNotFoundError:
        distribution = 'ros2lite'
    groups = {'ros2cli.command': COMMANDS}
    groups.update({group: verbs for group, (_command, verbs) in verb_tables().items()})
    for group in sorted(groups):
        click.echo(group)
        table = groups[group]
        for name in sorted(table):
            module, summary = table[name]
            click.echo(f'  {name}: {summary}')
            if verbose:
                click.echo(f'    module_name: {module}')
                click.echo('    attributes: cli')
                click.echo(f'    distribution: {distribution}')
