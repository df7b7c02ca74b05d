"""`node info`: what one node publishes, subscribes, serves and calls, in ros2cli's layout."""

from __future__ import annotations

import click

from .. import completion, render
from ..common import connect
from ..errors import CliError
from ..options import json_option, strategy_options
from ..parsing import command


def _section(title: str, items: list[tuple[str, list[str]]]) -> str:
    # ros2cli prints the (possibly empty) joined list, so an empty section is one blank line
    body = '\n'.join(f'    {name}: {", ".join(types)}' for name, types in items)
    return f'  {title}:\n{body}\n'


@command('info')
@strategy_options()
@click.argument('node_name', shell_complete=completion.nodes)
@click.option(
    '--include-hidden', is_flag=True, help='Also show hidden topics, services and actions'
)
@json_option(
    '{"name", "subscribers", "publishers", "service_servers", "service_clients", '
    '"action_servers", "action_clients"}, each [{"name", "types"}…]'
)
def cli(
    node_name: str, include_hidden: bool, no_daemon: bool, use_sim_time: bool, as_json: bool
) -> None:
    """Output information about a node."""
    from ros2lite.graph import node_full_names, node_info
    from ros2lite.names import split_fqn

    full = node_name if node_name.startswith('/') else '/' + node_name
    with connect(no_daemon=no_daemon) as conn:
        entities = conn.entities()
    count = node_full_names(entities, include_hidden=include_hidden).count(full)
    if count > 1:
        click.echo(
            f'There are {count} nodes in the graph with the exact name "{full}". '
            'You are seeing information about only one of them.',
            err=True,
        )
    namespace, name = split_fqn(full)
    info = node_info(entities, name, namespace, include_hidden) if count else None
    if info is None:
        raise CliError(f"Unable to find node '{full}'")
    if as_json:
        render.print_json(
            {
                'name': full,
                'subscribers': render.names_json(info.subscribers, False),
                'publishers': render.names_json(info.publishers, False),
                'service_servers': render.names_json(info.service_servers, False),
                'service_clients': render.names_json(info.service_clients, False),
                'action_servers': render.names_json(info.action_servers, False),
                'action_clients': render.names_json(info.action_clients, False),
            }
        )
        return
    render.echo(
        ''.join(
            [
                full + '\n',
                _section('Subscribers', info.subscribers),
                _section('Publishers', info.publishers),
                _section('Service Servers', info.service_servers),
                _section('Service Clients', info.service_clients),
                _section('Action Servers', info.action_servers),
                _section('Action Clients', info.action_clients),
            ]
        ),
        nl=False,
    )
