"""`security create_enclave ROOT NAME`: an enclave's key, certificate and permissions."""

from __future__ import annotations

from pathlib import Path

import click

from ..errors import CliError


@click.command('create_enclave')
@click.argument('root', metavar='ROOT', type=click.Path(path_type=Path))
@click.argument('name', metavar='NAME')
def cli(root: Path, name: str) -> None:
    """Create enclave."""
    from ros2lite.security import SecurityError
    from ros2lite.security.keystore import create_enclave

    try:
        create_enclave(root, name)
    except SecurityError as e:
        raise CliError(f'Unable to create enclave: {e}') from None
