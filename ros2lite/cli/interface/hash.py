"""`interface hash`: the RIHS01 hash, to compare with what a real ROS node advertises."""

from __future__ import annotations

import click

from ros2lite.interfaces import type_hash

from .. import completion
from ..parsing import command


@command('hash')
@click.argument('type_name', metavar='TYPE', shell_complete=completion.interface_types)
def cli(type_name: str) -> None:
    """Output the RIHS01 type hash of an interface (as used in rmw_zenoh keys)."""
    click.echo(type_hash(type_name))
