"""`security create_permission ROOT NAME POLICY_FILE_PATH`: an enclave's permissions from a
policy, signed by the keystore's permissions CA."""

from __future__ import annotations

from pathlib import Path

import click

from ..errors import CliError
from ..parsing import command


@command('create_permission')
@click.argument('root', metavar='ROOT', type=click.Path(path_type=Path))
@click.argument('name', metavar='NAME')
@click.argument('policy_file_path', metavar='POLICY_FILE_PATH', type=click.Path(path_type=Path))
def cli(root: Path, name: str, policy_file_path: Path) -> None:
    """Create permission."""
    from ros2lite.security import SecurityError
    from ros2lite.security.keystore import create_permission

    try:
        create_permission(root, name, policy_file_path)
    except SecurityError as e:
        raise CliError(f'Unable to create permission: {e}') from None
