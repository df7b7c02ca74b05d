"""`lifecycle list`: the transitions a managed node offers now (or all of them)."""

from __future__ import annotations

import click

from .. import completion, render
from ..common import connect
from ..errors import CliError
from ..options import json_option, strategy_options
from ..parsing import command
from .common import call_failed, require_node


@command('list')
@click.argument('node_name', shell_complete=completion.nodes)
@strategy_options()
@click.option('--include-hidden-nodes', is_flag=True, help='Consider hidden nodes as well')
@click.option('-a', '--all', 'show_all', is_flag=True, help='Display all existing transitions')
@json_option('[{"label", "id", "start", "goal"}…] (states by label)')
def cli(
    node_name: str,
    include_hidden_nodes: bool,
    show_all: bool,
    no_daemon: bool,
    use_sim_time: bool,
    as_json: bool,
) -> None:
    """Output a list of available transitions."""
    from ros2lite.client import ServiceCallError
    from ros2lite.lifecycle.remote import RemoteLifecycle

    with connect(no_daemon=no_daemon) as conn:
        full = require_node(conn, node_name, include_hidden_nodes)
        remote = RemoteLifecycle(conn.node(), full)
        try:
            found = remote.transition_graph() if show_all else remote.available_transitions()
        except (ServiceCallError, TimeoutError) as e:
            raise CliError(call_failed(node_name, e)) from None
    labels = remote.state_labels
    if as_json:
        render.print_json(
            [
                {
                    'label': t.label,
                    'id': t.id,
                    'start': labels.get(t.start, t.start),
                    'goal': labels.get(t.goal, t.goal),
                }
                for t in found
            ]
        )
        return
    for t in found:
        click.echo(
            f'- {t.label} [{t.id}]\n\tStart: {labels.get(t.start, t.start)}\n'
            f'\tGoal: {labels.get(t.goal, t.goal)}'
        )
