"""`service type`: the type of one service; like ros2cli it fails silently (exit 1) if unknown."""

from __future__ import annotations

import click

from .. import completion
from ..common import CliSession, strategy_options


@click.command('type')
@strategy_options()
@click.argument('service_name', shell_complete=completion.services)
@click.pass_context
def cli(ctx: click.Context, service_name: str, no_daemon: bool, use_sim_time: bool) -> None:
    """Output a service's type."""
    from ros2lite.graph import service_names_and_types
    from ros2lite.transport.keys import expand_topic_name
    try:
        name = expand_topic_name(service_name, 'ros2lite', '/')
    except ValueError:
        ctx.exit(1)  # a name that cannot be valid is just an unknown service here
    with CliSession(no_daemon=no_daemon) as session:
        entities = session.entities()
    for service, types in service_names_and_types(entities, include_hidden=True):
        if service == name:
            click.echo('\n'.join(types))
            return
    ctx.exit(1)

