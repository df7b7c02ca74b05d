"""`param set`: one or more `name value` pairs (values typed the YAML way), or `--atomic`."""

from __future__ import annotations

import click

from ..common import CliSession
from ..errors import CliError
from .common import connect, node_options


@click.command("set")
@node_options()
@click.argument("params_and_values", nargs=-1, required=True, metavar="NAME VALUE...")
@click.option(
    "--atomic",
    is_flag=True,
    help="Set all parameters atomically using the SetParametersAtomically service. "
    "Either all parameters are set successfully or none are changed.",
)
def cli(
    node_name: str,
    params_and_values: tuple[str, ...],
    atomic: bool,
    include_hidden_nodes: bool,
    timeout: int,
    service_timeout: float | None,
    no_daemon: bool,
    use_sim_time: bool,
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
    with CliSession(no_daemon=no_daemon, use_sim_time=use_sim_time) as session:
        remote = connect(session, node_name, include_hidden_nodes, timeout, service_timeout)
        if atomic:
            outcome = remote.set_parameters_atomically(params)
            results = None
        else:
            results = remote.set_parameters(params)
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
        # like ros2cli, a failed set still exits 0: the reason is on stderr
        click.echo(f"{name}: {text}" if len(pairs) > 1 else text, err=not result.successful)


def _message(text: str, reason: str) -> str:
    return f"{text}: {reason}" if reason else text
