"""`param describe`: type, description and constraints of declared parameters."""

from __future__ import annotations

from typing import TYPE_CHECKING

import click

from ..parsing import command

if TYPE_CHECKING:
    from ros2lite.msgs.rcl_interfaces.msg import (
        FloatingPointRange,
        IntegerRange,
        ParameterDescriptor,
    )

from ..options import json_option
from .common import Target, complete_parameter_names, node_options, type_name, with_remote


@command("describe")
@node_options()
@click.argument("parameter_names", nargs=-1, required=True, shell_complete=complete_parameter_names)
@json_option("[ParameterDescriptor…] (rcl_interfaces' fields, in the JSON form)")
def cli(
    parameter_names: tuple[str, ...],
    target: Target,
    as_json: bool,
) -> None:
    """Show descriptive information about declared parameters."""
    descriptors = with_remote(
        target,
        lambda r: r.call("describe_parameters", list(parameter_names)),
    ).descriptors
    if as_json:
        from ros2lite.interfaces.json_form import message_to_json

        from .. import render as draw

        draw.print_json([message_to_json(d) for d in descriptors])
        return
    # as ros2cli: a name the node does not know empties the reply, which prints nothing
    for descriptor in descriptors:
        click.echo("\n".join(render(descriptor)))


def render(d: ParameterDescriptor) -> list[str]:
    lines = [f"Parameter name: {d.name}", f"  Type: {type_name(d.type)}"]
    if d.description:
        lines.append(f"  Description: {d.description}")
    lines.append("  Constraints:")
    if d.read_only:
        lines.append("    Read only: true")
    ranges: list[FloatingPointRange | IntegerRange] = [*d.floating_point_range, *d.integer_range]
    if ranges:
        lines += [f"    Min value: {ranges[0].from_value}", f"    Max value: {ranges[0].to_value}"]
        if ranges[0].step:
            lines.append(f"    Step: {ranges[0].step}")
    if d.additional_constraints:
        lines.append(f"    Additional constraints: {d.additional_constraints}")
    return lines
