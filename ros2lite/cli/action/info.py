"""`action info`: who serves and who uses one action."""

from __future__ import annotations

import click

from .. import completion, render
from ..common import connect
from ..errors import CliError
from ..options import json_option, show_types_option, strategy_options
from ..parsing import command


def _section(
    title: str, rows: list[tuple[str, list[str]]], show_types: bool, count: bool
) -> list[str]:
    lines = [f'{title}: {len(rows)}']
    if not count:
        lines += [
            f'    {node} [{", ".join(types)}]' if show_types else f'    {node}'
            for node, types in rows
        ]
    return lines


@command('info')
@strategy_options()
@click.argument('action_name', shell_complete=completion.actions)
@show_types_option('action')
@click.option(
    '-c',
    '--count',
    is_flag=True,
    help='Only display the number of action clients and action servers',
)
@json_option(
    '{"name", "client_count", "server_count", "clients", "servers"}: each node as '
    '{"name", "types"} (-c: the counts alone)'
)
def cli(
    action_name: str,
    show_types: bool,
    count: bool,
    no_daemon: bool,
    use_sim_time: bool,
    as_json: bool,
) -> None:
    """Print information about an action."""
    from ros2lite.graph import action_endpoints
    from ros2lite.names import expand_topic_name, validate_full_topic_name

    try:
        name = expand_topic_name(action_name, 'ros2lite', '/')
        validate_full_topic_name(name)
    except ValueError as e:
        raise CliError(str(e)) from None
    with connect(no_daemon=no_daemon) as conn:
        entities = conn.entities()
    clients, servers = action_endpoints(entities, name)
    if as_json:
        doc: dict[str, object] = {
            'name': name,
            'client_count': len(clients),
            'server_count': len(servers),
        }
        if not count:
            doc['clients'] = render.names_json(clients, False)
            doc['servers'] = render.names_json(servers, False)
        render.print_json(doc)
        return
    # ros2cli echoes the name as it was given
    lines = [f'Action: {action_name}']
    lines += _section('Action clients', clients, show_types, count)
    lines += _section('Action servers', servers, show_types, count)
    render.echo('\n'.join(lines))
