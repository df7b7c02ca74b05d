"""`param dump`: every parameter of a node as a parameters file (stdout, or --output-dir)."""

from __future__ import annotations

from pathlib import Path

import click

from ..common import CliSession
from ..errors import CliError
from .common import connect, node_options


@click.command("dump")
@node_options()
@click.option(
    "--output-dir",
    metavar="DIR",
    type=click.Path(file_okay=False, path_type=Path),
    help="Write <node name>.yaml (namespace separators as __) into this directory "
    "instead of printing it",
)
def cli(
    node_name: str,
    output_dir: Path | None,
    include_hidden_nodes: bool,
    timeout: int,
    service_timeout: float | None,
    no_daemon: bool,
    use_sim_time: bool,
) -> None:
    """Show all of the parameters of a node in a YAML file format."""
    from ros2lite.parameters.files import dump_file_name

    with CliSession(no_daemon=no_daemon, use_sim_time=use_sim_time) as session:
        remote = connect(session, node_name, include_hidden_nodes, timeout, service_timeout)
        text = remote.dump_yaml()
    if output_dir is None:
        click.echo(text)  # yaml's text ends with a newline: a blank line follows, as ros2cli
        return
    path = output_dir / dump_file_name(remote.fqn)
    try:
        output_dir.mkdir(parents=True, exist_ok=True)
        path.write_text(text, encoding="utf-8")
    except OSError as e:
        raise CliError(f"Couldn't write '{path}': {e.strerror or e}") from None
