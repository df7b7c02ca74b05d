"""`topic find`: the topics that carry one exact type."""

from __future__ import annotations

import click

from .. import completion
from ..common import CliSession, include_hidden, strategy_options


@click.command('find')
@strategy_options()
@click.argument('topic_type', shell_complete=completion.message_types)
@click.option('-c', '--count-topics', is_flag=True, help='Print only how many topics match')
@click.option(
    '--include-hidden-topics',
    is_flag=True,
    help="Also match hidden topics (a name part starts with '_')",
)
@click.pass_context
def cli(
    ctx: click.Context,
    topic_type: str,
    count_topics: bool,
    include_hidden_topics: bool,
    no_daemon: bool,
    use_sim_time: bool,
) -> None:
    """Output a list of available topics of a given type."""
    from ros2lite.graph import topic_names_and_types

    with CliSession(no_daemon=no_daemon) as session:
        entities = session.entities()
    found = [
        name
        for name, types in topic_names_and_types(
            entities, include_hidden(ctx, include_hidden_topics)
        )
        if topic_type in types
    ]
    if count_topics:
        click.echo(len(found))
    elif found:
        click.echo('\n'.join(found))
