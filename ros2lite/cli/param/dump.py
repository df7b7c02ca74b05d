"""`param dump`: every parameter of a node as a parameters file (stdout, or --output-dir)."""

from __future__ import annotations

from pathlib import Path

import click

from ..errors import CliError
from ..options import json_option
from ..parsing import command
from .common import Remote, Target, node_options, python_json, with_remote


@command("dump")
@node_options()
@click.option(
    "--output-dir",
    metavar="DIR",
    type=click.Path(file_okay=False, path_type=Path),
    help="Write <node name>.yaml (namespace separators as __) into this directory "
    "instead of printing it",
)
@json_option('the parameters file\'s tree: {"/node": {"ros__parameters": {…}}}')
def cli(
    output_dir: Path | None,
    target: Target,
    as_json: bool,
) -> None:
    """Show all of the parameters of a node in a YAML file format."""
    from ros2lite.parameters.files import dump_file_name

    if as_json:
        if output_dir is not None:
            raise click.UsageError("--json prints to stdout: not with --output-dir")
        from ros2lite.parameters.files import PARAMS_KEY, dump_tree

        from .. import render

        fqn, values = with_remote(target, values_of)
        render.print_json({fqn: {PARAMS_KEY: python_json(dump_tree(values))}})
        return

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


def values_of(remote: Remote) -> tuple[str, dict[str, object]]:
    """(node name, its parameters' Python values by name)."""
    from ros2lite.parameter import parameter_value_to_python

    names = sorted(remote.call("list_parameters").result.names)
    values = remote.call("get_parameters", names).values if names else []
    return remote.fqn, {
        n: parameter_value_to_python(v) for n, v in zip(names, values, strict=False)
    }


def dump(remote: Remote) -> tuple[str, str]:
    """(node name, its parameters as a parameters file), as ros2cli dumps them."""
    from ros2lite.parameters.files import dump_yaml

    fqn, python = values_of(remote)
    return fqn, dump_yaml(fqn, python)
