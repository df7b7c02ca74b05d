"""`lifecycle set`: ask a managed node to take a transition, by label or by id."""

from __future__ import annotations

import click

from .. import completion
from ..common import connect
from ..errors import CliError
from ..options import strategy_options
from ..parsing import command
from .common import call_failed, require_node


@command('set')
@click.argument('node_name', shell_complete=completion.nodes)
@click.argument('transition')
@strategy_options()
@click.option('--include-hidden-nodes', is_flag=True, help='Consider hidden nodes as well')
def cli(
    node_name: str, transition: str, include_hidden_nodes: bool, no_daemon: bool, use_sim_time: bool
) -> None:
    """Trigger lifecycle state transition.

    TRANSITION is a label (configure, activate, deactivate, cleanup, shutdown) or an id among
    those the node offers now (`lifecycle list NODE_NAME`).
    """
    from ros2lite.client import ServiceCallError
    from ros2lite.lifecycle.remote import RemoteLifecycle

    with connect(no_daemon=no_daemon) as conn:
        full = require_node(conn, node_name, include_hidden_nodes)
        remote = RemoteLifecycle(conn.node(), full)
        try:
            offered = remote.available_transitions()
            chosen = next((t for t in offered if t.label == transition), None) or next(
                (t for t in offered if str(t.id) == transition), None
            )
            if chosen is None:
                raise CliError(
                    'Unknown transition requested, available ones are:'
                    + ''.join(f'\n- {t.label} [{t.id}]' for t in offered)
                )
            success = remote.change_state(chosen)
        except (ServiceCallError, TimeoutError) as e:
            raise CliError(call_failed(node_name, e)) from None
    if success:
        click.echo('Transitioning successful')
    else:
        # ros2cli reports a refused transition on stderr but still exits 0
        click.echo('Transitioning failed', err=True)
