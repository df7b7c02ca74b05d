"""`pkg list`: every package the index knows, one per line, sorted."""

from __future__ import annotations

import click

from ..parsing import command


@command('list')
def cli() -> None:
    """Output a list of available packages."""
    from ros2lite.pkg.executables import list_packages

    for name in list_packages():
        click.echo(name)
