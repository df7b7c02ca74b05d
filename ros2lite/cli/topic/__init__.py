"""`ros2lite topic`: inspect and exercise topics."""

from __future__ import annotations

import click

from ..lazy import LazyGroup

VERBS = {
    'bw': (__name__ + '.bw', 'Display bandwidth used by topic'),
    'delay': (__name__ + '.delay', 'Display delay of topic from timestamp in header'),
    'echo': (__name__ + '.echo', 'Output messages from a topic'),
    'find': (__name__ + '.find', 'Output a list of available topics of a given type'),
    'hz': (__name__ + '.hz', 'Print the average receiving rate to screen'),
    'info': (__name__ + '.info', 'Print information about a topic'),
    'list': (__name__ + '.list', 'Output a list of available topics'),
    'pub': (__name__ + '.pub', 'Publish a message to a topic'),
    'type': (__name__ + '.type', "Print a topic's type"),
}


@click.group(cls=LazyGroup, lazy=VERBS, invoke_without_command=True)
@click.option('--include-hidden-topics', is_flag=True, help='Consider hidden topics as well')
@click.pass_context
def cli(ctx: click.Context, include_hidden_topics: bool) -> None:
    """Various topic related sub-commands."""
    ctx.ensure_object(dict)['include_hidden_topics'] = include_hidden_topics
    if ctx.invoked_subcommand is None:
        click.echo(ctx.get_help())
