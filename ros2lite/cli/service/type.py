"""`service type`: the type of one service; exit 1 with one line on stderr if unknown."""

from __future__ import annotations

import click

from .. import completion
from ..common import print_types_of
from ..options import json_option, strategy_options
from ..parsing import command


@command('type')
@strategy_options()
@click.argument('service_name', shell_complete=completion.services)
@json_option('{"name", "types"}')
def cli(service_name: str, no_daemon: bool, use_sim_time: bool, as_json: bool) -> None:
    """Output a service's type."""
    from ros2lite.graph import service_names_and_types

    print_types_of(
        service_name,
        no_daemon,
        lambda entities: service_names_and_types(entities, include_hidden=True),
        'service',
        as_json,
    )
