"""What the security verbs share."""

from __future__ import annotations

from pathlib import Path

from ..errors import CliError


def create(root: Path, name: str, what: str) -> None:
    """Create the enclave `name` in the keystore `root`; sros2's error line names `what`
    was being created (`create_key` is the older name of this verb)."""
    from ros2lite.security import SecurityError
    from ros2lite.security.keystore import create_enclave

    try:
        create_enclave(root, name)
    except SecurityError as e:
        raise CliError(f'Unable to create {what}: {e}') from None
