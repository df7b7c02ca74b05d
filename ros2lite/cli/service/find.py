"""`service find`: the services of one type."""

from __future__ import annotations

import click

from .. import completion
from ..common import CliSession, strategy_options
from . import hidden_wanted


@click.command('find')
@strategy_options()
@click.argument('service_type', shell_complete=completion.service_types)
@click.option(
    '-c', '--count-services', is_flag=True, help='Only display the number of services discovered'
)
@click.option('--include-hidden-services', is_flag=True, help='Consider hidden services as well')
@click.pass_context
def cli(
    ctx: click.Context,
    service_type: str,
    count_services: bool,
    include_hidden_services: bool,
    no_daemon: bool,
    use_sim_time: bool,
) -> None:
    """Output a list of available services of a given type."""
    from ros2lite.graph import service_names_and_types

    with CliSession(no_daemon=no_daemon) as session:
        entities = session.entities()
    found = [
        name
        for name, types in service_names_and_types(
            entities, hidden_wanted(ctx, include_hidden_services)
        )
        if service_type in types
    ]
    if count_services:
        click.echo(len(found))
    elif found:
        click.echo('\n'.join(found))
