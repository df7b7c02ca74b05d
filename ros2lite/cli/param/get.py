"""`param get`: one parameter's value, labelled with its type as ros2cli prints it."""

from __future__ import annotations

from typing import Any

import click

from ..common import CliSession
from ..errors import CliError
from .common import complete_parameter_names, connect, node_options

# ParameterType number → the label before the value
LABELS = {
    1: "Boolean value is:",
    2: "Integer value is:",
    3: "Double value is:",
    4: "String value is:",
    5: "Byte values are:",
    6: "Boolean values are:",
    7: "Integer values are:",
    8: "Double values are:",
    9: "String values are:",
}


@click.command("get")
@node_options()
@click.argument("parameter_name", shell_complete=complete_parameter_names)
@click.option("--hide-type", is_flag=True, help="Hide the type information")
def cli(
    node_name: str,
    parameter_name: str,
    hide_type: bool,
    include_hidden_nodes: bool,
    timeout: int,
    service_timeout: float | None,
    no_daemon: bool,
    use_sim_time: bool,
) -> None:
    """Get parameter."""
    with CliSession(no_daemon=no_daemon, use_sim_time=use_sim_time) as session:
        remote = connect(session, node_name, include_hidden_nodes, timeout, service_timeout)
        values = remote.get_parameters([parameter_name])
    if not values:
        raise CliError("Parameter not set")
    click.echo(render(values[0], hide_type))


def render(value: Any, hide_type: bool) -> str:
    from ros2lite.parameter import parameter_value_to_python

    if value.type not in LABELS and value.type != 0:
        raise CliError(f"Unknown parameter type '{value.type}'")
    python = parameter_value_to_python(value)
    if hide_type:
        return str(python)
    if value.type == 0:
        return "Parameter not set."
    return f"{LABELS[value.type]} {python}"
