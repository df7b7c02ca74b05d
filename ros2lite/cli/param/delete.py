"""`param delete`: undeclare a parameter (set it to NOT_SET), if the node allows it."""

from __future__ import annotations

import click

from ..parsing import command
from .common import Target, complete_parameter_names, node_options, with_remote


@command("delete")
@node_options()
@click.argument("parameter_name", shell_complete=complete_parameter_names)
def cli(
    parameter_name: str,
    target: Target,
) -> None:
    """Delete parameter."""
    from ros2lite.parameter import Parameter

    result = with_remote(
        target,
        lambda r: r.call("set_parameters", [Parameter(parameter_name)]),
    ).results[0]
    text = "Deleted parameter successfully" if result.successful else "Deleting parameter failed"
    # a refusal goes to stderr with exit status 0, as ros2cli's
    click.echo(f"{text}: {result.reason}" if result.reason else text, err=not result.successful)
