"""`security list_enclaves ROOT`: every enclave of a keystore, one a line, sorted."""

from __future__ import annotations

from pathlib import Path

import click

from ..errors import CliError
from ..options import json_option
from ..parsing import command


@command('list_enclaves')
@click.argument('root', metavar='ROOT', type=click.Path(path_type=Path))
@json_option('["/enclave", …]')
def cli(root: Path, as_json: bool) -> None:
    """List enclaves in keystore."""
    from ros2lite.security import SecurityError
    from ros2lite.security.keystore import list_enclaves

    try:
        enclaves = list_enclaves(root)
    except SecurityError as e:
        raise CliError(f'Unable to list enclaves: {e}') from None
    if as_json:
        from .. import render

        render.print_json(list(enclaves))
        return
    for enclave in enclaves:
        click.echo(enclave)
