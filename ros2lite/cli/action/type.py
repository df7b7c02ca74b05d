"""`action type`: the type(s) of one action; like ros2cli it fails silently (exit 1) if
unknown."""

from __future__ import annotations

import click

from .. import completion
from ..common import CliSession, strategy_options


@click.command('type')
@strategy_options()
@click.argument('action_name', shell_complete=completion.actions)
@click.pass_context
def cli(ctx: click.Context, action_name: str, no_daemon: bool, use_sim_time: bool) -> None:
    """Print a action's type."""
    from ros2lite.graph import action_names_and_types
    from ros2lite.transport.keys import expand_topic_name
    try:
        name = expand_topic_name(action_name, 'ros2lite', '/')
    except ValueError:
        ctx.exit(1)  # a name that cannot be valid is just an unknown action here
    with CliSession(no_daemon=no_daemon) as session:
        entities = session.entities()
    types = dict(action_names_and_types(entities)).get(name)
    if types is None:
        ctx.exit(1)
    click.echo('\n'.join(types))
