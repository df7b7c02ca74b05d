"""`service find`: the services of one type."""

from __future__ import annotations

import click

from .. import completion
from ..common import print_names_of_type
from ..lazy import include_hidden, include_hidden_option
from ..options import count_option, json_option, strategy_options
from ..parsing import command


@command('find')
@strategy_options()
@click.argument('service_type', shell_complete=completion.service_types)
@count_option('services')
@include_hidden_option('services')
@json_option('[{"name", "types"}…] or {"count"}')
@click.pass_context
def cli(
    ctx: click.Context,
    service_type: str,
    count_services: bool,
    include_hidden_services: bool,
    no_daemon: bool,
    use_sim_time: bool,
    as_json: bool,
) -> None:
    """Output a list of available services of a given type."""
    from ros2lite.graph import service_names_and_types

    print_names_of_type(
        service_type,
        count_services,
        no_daemon,
        lambda entities: service_names_and_types(
            entities, include_hidden(ctx, 'services', include_hidden_services)
        ),
        as_json,
    )
