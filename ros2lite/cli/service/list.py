"""`service list`: the services in the graph (servers and clients), optionally with types."""

from __future__ import annotations

import click

from ..common import connect, print_names, strategy_options
from . import hidden_wanted


@click.command('list')
@strategy_options()
@click.option('-t', '--show-types', is_flag=True, help='Additionally show the service type')
@click.option(
    '-c', '--count-services', is_flag=True, help='Only display the number of services discovered'
)
@click.option('--include-hidden-services', is_flag=True, help='Consider hidden services as well')
@click.pass_context
def cli(
    ctx: click.Context,
    show_types: bool,
    count_services: bool,
    include_hidden_services: bool,
    no_daemon: bool,
    use_sim_time: bool,
) -> None:
    """Output a list of available services."""
    from ros2lite.graph import service_names_and_types

    with connect(no_daemon=no_daemon) as conn:
        entities = conn.entities()
    services = service_names_and_types(entities, hidden_wanted(ctx, include_hidden_services))
    print_names(services, count_services, show_types)
