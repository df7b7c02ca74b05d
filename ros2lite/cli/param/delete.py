"""`param delete`: undeclare a parameter (set it to NOT_SET), if the node allows it."""

from __future__ import annotations

import click

from ..common import CliSession
from .common import complete_parameter_names, connect, node_options


@click.command("delete")
@node_options()
@click.argument("parameter_name", shell_complete=complete_parameter_names)
def cli(
    node_name: str,
    parameter_name: str,
    include_hidden_nodes: bool,
    timeout: int,
    service_timeout: float | None,
    no_daemon: bool,
    use_sim_time: bool,
) -> None:
    """Delete parameter."""
    with CliSession(no_daemon=no_daemon, use_sim_time=use_sim_time) as session:
        remote = connect(session, node_name, include_hidden_nodes, timeout, service_timeout)
        result = remote.delete_parameters([parameter_name])[0]
    text = "Deleted parameter successfully" if result.successful else "Deleting parameter failed"
    click.echo(f"{text}: {result.reason}" if result.reason else text, err=not result.successful)
