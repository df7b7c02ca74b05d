"""`topic type`: the type(s) of one topic; like ros2cli it fails silently (exit 1) if unknown."""

from __future__ import annotations

import click

from .. import completion
from ..common import CliSession, include_hidden, strategy_options


@click.command('type')
@strategy_options()
@click.argument('topic_name', shell_complete=completion.topics)
@click.pass_context
def cli(ctx: click.Context, topic_name: str, no_daemon: bool, use_sim_time: bool) -> None:
    """Print a topic's type."""
    from ros2lite.graph import topic_names_and_types
    from ros2lite.transport.keys import expand_topic_name
    try:
        name = expand_topic_name(topic_name, 'ros2lite', '/')
    except ValueError:
        ctx.exit(1)  # a name that cannot be valid is just an unknown topic here
    with CliSession(no_daemon=no_daemon) as session:
        entities = session.entities()
    for topic, types in topic_names_and_types(entities, include_hidden(ctx)):
        if topic == name:
            click.echo('\n'.join(types))
            return
    ctx.exit(1)
