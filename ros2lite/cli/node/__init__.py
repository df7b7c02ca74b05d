"""`ros2lite node`: the nodes in the graph."""

from __future__ import annotations

import click

from ..lazy import LazyGroup

VERBS = {
    'info': (__name__ + '.info', 'Output information about a node'),
    'list': (__name__ + '.list', 'Output a list of available nodes'),
}


@click.group(cls=LazyGroup, lazy=VERBS, invoke_without_command=True)
@click.pass_context
def cli(ctx: click.Context) -> None:
    """Various node related sub-commands."""
    if ctx.invoked_subcommand is None:
        click.echo(ctx.get_help())
