"""`param dump`: every parameter of a node as a parameters file (stdout, or --output-dir)."""

from __future__ import annotations

from pathlib import Path

import click

from ..errors import CliError
from ..parsing import command
from .common import Remote, Target, node_options, with_remote


@command("dump")
@node_options()
@click.option(
    "--output-dir",
    metavar="DIR",
    type=click.Path(file_okay=False, path_type=Path),
    help="Write <node name>.yaml (namespace separators as __) into this directory "
    "instead of printing it",
)
def cli(
    output_dir: Path | None,
    target: Target,
) -> None:
    """Show all of the parameters of a node in a YAML file format."""
    from ros2lite.parameters.files import dump_file_name

    fqn, text = with_remote(target, dump)
    if output_dir is None:
        click.echo(text)  # yaml's text ends with a newline: a blank line follows, as ros2cli
        return
    path = output_dir / dump_file_name(fqn)
    try:
        from ros2lite.util.files import open_for_writing

        output_dir.mkdir(parents=True, exist_ok=True)
        with open(open_for_writing(path), "w", encoding="utf-8") as f:
            f.write(text)
    except OSError as e:
        raise CliError(f"Couldn't write '{path}': {e.strerror or e}") from None


def dump(remote: Remote) -> tuple[str, str]:
    """(node name, its parameters as a parameters file), as ros2cli dumps them."""
    from ros2lite.parameter import parameter_value_to_python
    from ros2lite.parameters.files import dump_yaml

    names = sorted(remote.call("list_parameters").result.names)
    values = remote.call("get_parameters", names).values if names else []
    python = {n: parameter_value_to_python(v) for n, v in zip(names, values, strict=False)}
    return remote.fqn, dump_yaml(remote.fqn, python)
