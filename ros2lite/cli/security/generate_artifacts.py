"""`security generate_artifacts [-k ROOT] [-e NAME…] [-p POLICY…]`: enclaves and their
permissions in one go (the keystore is created when it is not one yet)."""

from __future__ import annotations

from pathlib import Path

import click

from ..errors import CliError
from ..parsing import ManyValues, command


@command('generate_artifacts')
@click.option(
    '-k',
    '--keystore-root-path',
    type=click.Path(path_type=Path),
    default=None,
    help='root path of keystore (default: $ROS_SECURITY_KEYSTORE)',
)
@click.option(
    '-e',
    '--enclaves',
    cls=ManyValues,
    at_least=0,
    help='list of identities, aka ROS security enclave names',
)
@click.option(
    '-p',
    '--policy-files',
    cls=ManyValues,
    at_least=0,
    type=click.Path(path_type=Path),
    help='list of policy xml file paths',
)
def cli(
    keystore_root_path: Path | None, enclaves: tuple[str, ...], policy_files: tuple[Path, ...]
) -> None:
    """Generate keys and permission files from a list of identities and policy files."""
    from ros2lite.security import SecurityError
    from ros2lite.security.keystore import generate_artifacts

    try:
        generate_artifacts(
            keystore_root_path, list(enclaves), list(policy_files), notify=click.echo
        )
    except SecurityError as e:
        raise CliError(f'Unable to generate artifacts: {e}') from None
