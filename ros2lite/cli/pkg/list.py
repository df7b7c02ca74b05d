"""`pkg list`: every package the index knows, one per line, sorted."""

from __future__ import annotations

import click

from ..options import json_option
from ..parsing import command


@command('list')
@json_option('["package", …]')
def cli(as_json: bool) -> None:
    """Output a list of available packages."""
    from ros2lite.pkg.executables import list_packages

    if as_json:
        from .. import render

        render.print_json(list(list_packages()))
        return

    for name in list_packages():
        click.echo(name)
