"""`param get`: one parameter's value, labelled with its type as ros2cli prints it."""

from __future__ import annotations

from typing import TYPE_CHECKING

import click

from ..parsing import command

if TYPE_CHECKING:
    from ros2lite.msgs.rcl_interfaces.msg import ParameterValue

from ..errors import CliError
from ..options import json_option
from .common import (
    Target,
    complete_parameter_names,
    node_options,
    python_json,
    type_name,
    with_remote,
)

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


@command("get")
@node_options()
@click.argument("parameter_name", shell_complete=complete_parameter_names)
@click.option("--hide-type", is_flag=True, help="Hide the type information")
@json_option('{"name", "type", "value"} (type "not set" and value null when unset)')
def cli(
    parameter_name: str,
    hide_type: bool,
    target: Target,
    as_json: bool,
) -> None:
    """Get parameter."""
    values = with_remote(target, lambda r: r.call("get_parameters", [parameter_name])).values
    if not values:
        raise CliError("Parameter not set")
    if as_json:
        from ros2lite.parameter import parameter_value_to_python

        from .. import render as draw

        value = values[0]
        draw.print_json(
            {
                "name": parameter_name,
                "type": type_name(value.type),
                "value": python_json(parameter_value_to_python(value)),
            }
        )
        return
    click.echo(render(values[0], hide_type))


def render(value: ParameterValue, hide_type: bool) -> str:
    from ros2lite.parameter import parameter_value_to_python

    if value.type not in LABELS and value.type != 0:
        raise CliError(f"Unknown parameter type '{value.type}'")
    python = parameter_value_to_python(value)
    if hide_type:
        return str(python)
    if value.type == 0:
        return "Parameter not set."
    return f"{LABELS[value.type]} {python}"
