"""`security create_key ROOT NAME`: the name sros2 used before `create_enclave`."""

from __future__ import annotations

from pathlib import Path

import click

from ..errors import CliError


@click.command('create_key')
@click.argument('root', metavar='ROOT', type=click.Path(path_type=Path))
@click.argument('name', metavar='NAME')
def cli(root: Path, name: str) -> None:
    """Create key (the older name of create_enclave; NAME is the enclave)."""
    from ros2lite.security import SecurityError
    from ros2lite.security.keystore import create_enclave

    try:
        create_enclave(root, name)
    except SecurityError as e:
        raise CliError(f'Unable to create key: {e}') from None
