"""`security create_key ROOT NAME`: the name sros2 used before `create_enclave`."""

from __future__ import annotations

from pathlib import Path

import click

from ..parsing import command
from .common import create


@command('create_key')
@click.argument('root', metavar='ROOT', type=click.Path(path_type=Path))
@click.argument('name', metavar='NAME')
def cli(root: Path, name: str) -> None:
    """Create key (the older name of create_enclave; NAME is the enclave)."""
    create(root, name, 'key')
