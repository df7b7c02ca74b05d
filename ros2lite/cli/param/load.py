"""`param load`: set a node's parameters from a parameters file (with `/**` entries unless
--no-use-wildcard), reporting each one."""

from __future__ import annotations

import click

from ..common import CliSession
from ..errors import CliError
from .common import connect, node_options


@click.command("load")
@node_options()
@click.argument("parameter_file")
@click.option(
    "--no-use-wildcard",
    is_flag=True,
    help="Do not load parameters in the '/**' namespace into the node",
)
def cli(
    node_name: str,
    parameter_file: str,
    no_use_wildcard: bool,
    include_hidden_nodes: bool,
    timeout: int,
    service_timeout: float | None,
    no_daemon: bool,
    use_sim_time: bool,
) -> None:
    """Load parameter file for a node."""
    from ros2lite.parameters.files import ParamsFileError

    with CliSession(no_daemon=no_daemon, use_sim_time=use_sim_time) as session:
        remote = connect(session, node_name, include_hidden_nodes, timeout, service_timeout)
        try:
            results = remote.load_parameter_file(parameter_file, use_wildcard=not no_use_wildcard)
        except ParamsFileError as e:
            raise CliError(str(e)) from None
    for name, result in results:
        text = (
            f"Set parameter {name} successful"
            if result.successful
            else f"Set parameter {name} failed"
        )
        click.echo(f"{text}: {result.reason}" if result.reason else text, err=not result.successful)
