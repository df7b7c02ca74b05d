"""Enclaves and where their material lies: the naming rules the keystore, the policies and the
process's security settings share.

An enclave is named like a namespace (``/``, ``/talker``, ``/robot/arm``); its certificate and
key live in ``$ROS_SECURITY_KEYSTORE/enclaves/<enclave>``.
"""

from __future__ import annotations

import os
from collections.abc import Mapping
from pathlib import Path

from ros2lite.exceptions import NameValidationException
from ros2lite.names import validate_namespace
from ros2lite.security.errors import EnclaveError, KeystoreError
from ros2lite.util.domain import DDS_MAX_DOMAIN_ID, parse_domain_id

__all__ = ['KEYSTORE_ENV', 'enclave_directory', 'env_domain_id', 'validate_enclave_name']

KEYSTORE_ENV = 'ROS_SECURITY_KEYSTORE'


def env_domain_id(env: Mapping[str, str] | None = None) -> int:
    """``ROS_DOMAIN_ID`` as sros2 writes it into documents and as a secured process checks
    its permissions against (0 when unset): read as rcl reads it, as the transport does, so
    the domain checked is the domain joined; documents hold DDS's domains, 0..232."""
    raw = (os.environ if env is None else env).get('ROS_DOMAIN_ID', '')
    try:
        value = parse_domain_id(raw)
    except ValueError as e:
        raise KeystoreError(str(e)) from None
    if value > DDS_MAX_DOMAIN_ID:
        raise KeystoreError(
            f'ROS_DOMAIN_ID {raw!r} is domain {value}: security documents hold domains '
            f'0..{DDS_MAX_DOMAIN_ID}'
        )
    return value


def validate_enclave_name(name: str) -> None:
    """An enclave name follows the namespace rules (absolute, no empty or '..' parts)."""
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
