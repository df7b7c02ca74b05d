"""Enclaves and where their material lies: the naming rules the keystore, the policies and the
process's security settings share.

An enclave is named like a namespace (``/``, ``/talker``, ``/robot/arm``); its certificate and
key live in ``$ROS_SECURITY_KEYSTORE/enclaves/<enclave>``.
"""

from __future__ import annotations

from pathlib import Path

from ros2lite.security.errors import EnclaveError

__all__ = ['KEYSTORE_ENV', 'enclave_directory', 'validate_enclave_name']

KEYSTORE_ENV = 'ROS_SECURITY_KEYSTORE'


def validate_enclave_name(name: str) -> None:
    """An enclave name follows the namespace rules (absolute, no empty or '..' parts)."""
    from ros2lite.exceptions import NameValidationException
    from ros2lite.names import validate_namespace

    try:
        validate_namespace(name)
    except NameValidationException as exc:
        raise EnclaveError(f"'{name}' is not a valid enclave name: {exc}") from None


def enclave_directory(keystore: Path, enclave: str) -> Path:
    """``<keystore>/enclaves/<enclave>`` (``/`` is the enclaves directory itself)."""
    validate_enclave_name(enclave)
    relative = enclave.strip('/')
    base = keystore / 'enclaves'
    return base / relative if relative else base
