"""`param set`: one or more `name value` pairs (values typed the YAML way), or `--atomic`."""

from __future__ import annotations

import click

from ..errors import CliError
from ..parsing import command
from .common import Target, complete_pair_names, node_options, with_remote


@command("set")
@node_options()
@click.argument(
    "params_and_values",
    nargs=-1,
    required=True,
    metavar="NAME VALUE...",
    shell_complete=complete_pair_names,
)
@click.option(
    "--atomic",
    is_flag=True,
    help="Set all parameters atomically using the SetParametersAtomically service. "
    "Either all parameters are set successfully or none are changed.",
)
def cli(
    params_and_values: tuple[str, ...],
    atomic: bool,
    target: Target,
) -> None:
    """Set parameter."""
    from ros2lite.interfaces import get_interface
    from ros2lite.parameter import get_parameter_value

    if len(params_and_values) % 2:
        raise CliError(
            "Parameters must be provided as name/value pairs: name value "
            f"[name value ...]. Got {len(params_and_values)} argument(s)."
        )
    pairs = list(zip(params_and_values[::2], params_and_values[1::2], strict=False))
    msg_type = get_interface("rcl_interfaces/msg/Parameter")
    params = [msg_type(name=name, value=get_parameter_value(text)) for name, text in pairs]
    if atomic:
        outcome = with_remote(
            target,
            lambda r: r.call("set_parameters_atomically", params),
        ).result
        results = None
    else:
        results = with_remote(target, lambda r: r.call("set_parameters", params)).results
    if results is None:
        if outcome.successful:
            click.echo(_message("Set parameters atomically successful", outcome.reason))
        else:
            click.echo(_message("Setting parameters atomically failed", outcome.reason), err=True)
        return
    for (name, _), result in zip(pairs, results, strict=False):
        text = _message(
            "Set parameter successful" if result.successful else "Setting parameter failed",
            result.reason,
        )
        # a refusal is the node's answer, not a failure of the verb: its reason goes to stderr
        # and the exit status stays 0, as ros2cli's (scripts written for ros2 rely on it)
        click.echo(f"{name}: {text}" if len(pairs) > 1 else text, err=not result.successful)


def _message(text: str, reason: str) -> str:
    return f"{text}: {reason}" if reason else text
