"""`security create_enclave ROOT NAME`: an enclave's key, certificate and permissions."""

from __future__ import annotations

from pathlib import Path

import click

from ..parsing import command
from .common import create


@command('create_enclave')
@click.argument('root', metavar='ROOT', type=click.Path(path_type=Path))
@click.argument('name', metavar='NAME')
def cli(root: Path, name: str) -> None:
    """Create enclave."""
    create(root, name, 'enclave')
