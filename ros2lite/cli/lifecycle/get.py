"""`lifecycle get`: the state of one managed node, or of every one."""

from __future__ import annotations

import click

from .. import completion, render
from ..common import connect
from ..errors import CliError
from ..options import json_option, strategy_options
from ..parsing import command
from .common import NODE_NOT_FOUND, absolute, call_failed, managed_nodes


@command('get')
@click.argument('node_name', required=False, shell_complete=completion.nodes)
@strategy_options()
@click.option(
    '--include-hidden-nodes', '-a', '--all', is_flag=True, help='Consider hidden nodes as well'
)
@click.option(
    '--timeout',
    type=click.FloatRange(min=0, min_open=True),
    metavar='N',
    help='Maximum time to wait for response in seconds (default: waits indefinitely)',
)
@json_option('{"/node": {"label", "id"}} (each managed node, or NODE_NAME\'s)')
def cli(
    node_name: str | None,
    include_hidden_nodes: bool,
    timeout: float | None,
    no_daemon: bool,
    use_sim_time: bool,
    as_json: bool,
) -> None:
    """Get lifecycle state for one or more nodes.

    Without NODE_NAME, the state of every managed node, one `name: state [id]` a line.
    """
    from ros2lite.client import ServiceCallError
    from ros2lite.lifecycle.remote import RemoteLifecycle

    with connect(no_daemon=no_daemon) as conn:
        names = managed_nodes(conn, include_hidden_nodes)
        if node_name is not None:
            if absolute(node_name) not in names:
                raise CliError(NODE_NOT_FOUND)
            names = [absolute(node_name)]
        states: dict[str, object] = {}
        for name in names:
            try:
                state = RemoteLifecycle(conn.node(), name).get_state(timeout)
            except (ServiceCallError, TimeoutError) as e:
                if node_name is not None:
                    raise CliError(call_failed(name, e)) from None
                click.echo(call_failed(name, e), err=True)
                continue
            if as_json:
                states[name] = {'label': state.label, 'id': state.state_id}
                continue
            prefix = '' if node_name is not None else f'{name}: '
            click.echo(f'{prefix}{state.label} [{state.state_id}]')
    if as_json:
        render.print_json(states)
