"""`param load`: set a node's parameters from a parameters file (with `/**` entries unless
--no-use-wildcard), reporting each one."""

from __future__ import annotations

from typing import TYPE_CHECKING

import click

from ..parsing import command

if TYPE_CHECKING:
    from ros2lite.msgs.rcl_interfaces.msg import SetParametersResult

from .common import Remote, Target, node_options, with_remote


@command("load")
@node_options()
@click.argument("parameter_file")
@click.option(
    "--no-use-wildcard",
    is_flag=True,
    help="Do not load parameters in the '/**' namespace into the node",
)
def cli(
    parameter_file: str,
    no_use_wildcard: bool,
    target: Target,
) -> None:
    """Load parameter file for a node."""

    def load(remote: Remote) -> list[tuple[str, SetParametersResult]]:
        params = remote.client.file_parameters(parameter_file, not no_use_wildcard)
        response = remote.call("set_parameters", params)
        return list(zip([p.name for p in params], response.results, strict=False))

    for name, result in with_remote(target, load):
        text = (
            f"Set parameter {name} successful"
            if result.successful
            else f"Set parameter {name} failed"
        )
        click.echo(f"{text}: {result.reason}" if result.reason else text, err=not result.successful)
