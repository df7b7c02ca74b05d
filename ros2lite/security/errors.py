"""Errors of the security package, under ros2lite's one base (each message is one line)."""

from __future__ import annotations

from ros2lite.exceptions import Ros2liteError

__all__ = ['EnclaveError', 'KeystoreError', 'PolicyError', 'SecurityError']


class SecurityError(Ros2liteError, RuntimeError):
    """Security is asked for but cannot be had as asked (missing material, bad files)."""


class KeystoreError(SecurityError):
    """A keystore is missing, incomplete, or cannot be written."""


class EnclaveError(SecurityError):
    """An enclave name is invalid, or the enclave's files are missing or unusable."""


class PolicyError(SecurityError):
    """A policy or permissions document is malformed; the message names the file and why."""
