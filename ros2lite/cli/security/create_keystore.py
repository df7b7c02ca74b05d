"""`security create_keystore ROOT`: a new sros2-layout keystore (CA and signed governance)."""

from __future__ import annotations

from pathlib import Path

import click

from ..errors import CliError
from ..parsing import command


@command('create_keystore')
@click.argument('root', metavar='ROOT', type=click.Path(path_type=Path))
def cli(root: Path) -> None:
    """Create keystore."""
    from ros2lite.security import SecurityError
    from ros2lite.security.keystore import create_keystore

    try:
        create_keystore(root)
    except SecurityError as e:
        raise CliError(f'Unable to create keystore: {e}') from None
