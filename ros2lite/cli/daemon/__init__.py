"""`ros2lite daemon`: the local Zenoh router that every ros2lite session connects to."""

from __future__ import annotations

import click

from ..lazy import LazyGroup

VERBS = {
    'start': (__name__ + '.start', 'Start the daemon if it isn\'t running'),
    'status': (__name__ + '.status', 'Output the status of the daemon'),
    'stop': (__name__ + '.stop', 'Stop the daemon if it is running'),
}


@click.group(cls=LazyGroup, lazy=VERBS, invoke_without_command=True)
@click.pass_context
def cli(ctx: click.Context) -> None:
    """Various daemon related sub-commands."""
    if ctx.invoked_subcommand is None:
        click.echo(ctx.get_help())
