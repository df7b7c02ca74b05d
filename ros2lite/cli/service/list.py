"""`service list`: the services in the graph (servers and clients), optionally with types."""

from __future__ import annotations

import click

from ..common import connect
from ..lazy import include_hidden, include_hidden_option
from ..options import count_option, json_option, show_types_option, strategy_options
from ..parsing import command
from ..render import print_names


@command('list')
@strategy_options()
@show_types_option('service')
@count_option('services')
@include_hidden_option('services')
@json_option('[{"name", "types"}…] or {"count"}')
@click.pass_context
def cli(
    ctx: click.Context,
    show_types: bool,
    count_services: bool,
    include_hidden_services: bool,
    no_daemon: bool,
    use_sim_time: bool,
    as_json: bool,
) -> None:
    """Output a list of available services."""
    from ros2lite.graph import service_names_and_types

    with connect(no_daemon=no_daemon) as conn:
        entities = conn.entities()
    services = service_names_and_types(
        entities, include_hidden(ctx, 'services', include_hidden_services)
    )
    print_names(services, count_services, show_types, as_json)
