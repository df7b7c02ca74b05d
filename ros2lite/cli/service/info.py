"""`service info`: type and how many clients and servers a service has."""

from __future__ import annotations

import click

from .. import completion, render
from ..common import connect
from ..errors import CliError
from ..options import json_option, strategy_options
from ..parsing import command


@command('info')
@strategy_options()
@click.argument('service_name', shell_complete=completion.services)
@json_option('{"name", "types", "client_count", "service_count"}')
@click.pass_context
def cli(
    ctx: click.Context, service_name: str, no_daemon: bool, use_sim_time: bool, as_json: bool
) -> None:
    """Print information about a service."""
    from ros2lite.graph import EntityKind, count, service_names_and_types
    from ros2lite.names import expand_topic_name

    try:
        name = expand_topic_name(service_name, 'ros2lite', '/')
    except ValueError:
        raise CliError(f"Unknown service '{service_name}'") from None
    with connect(no_daemon=no_daemon) as conn:
        entities = conn.entities()
    types = dict(service_names_and_types(entities, include_hidden=True)).get(name)
    if types is None:
        raise CliError(f"Unknown service '{name}'")
    if as_json:
        render.print_json(
            {
                'name': name,
                'types': types,
                'client_count': count(entities, name, EntityKind.CLIENT),
                'service_count': count(entities, name, EntityKind.SERVICE),
            }
        )
        return
    click.echo(f'Type: {", ".join(types)}')
    click.echo(f'Clients count: {count(entities, name, EntityKind.CLIENT)}')
    click.echo(f'Services count: {count(entities, name, EntityKind.SERVICE)}')
