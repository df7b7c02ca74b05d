"""sros2's keystore, made and read with the same layout and files::

    <keystore>/public/ca.cert.pem            the CA certificate
    <keystore>/public/{identity,permissions}_ca.cert.pem  → ca.cert.pem
    <keystore>/private/ca.key.pem            the CA key (0600)
    <keystore>/private/{identity,permissions}_ca.key.pem  → ca.key.pem
    <keystore>/enclaves/governance.{xml,p7s}
    <keystore>/enclaves/<enclave>/cert.pem, key.pem
    <keystore>/enclaves/<enclave>/{identity,permissions}_ca.cert.pem, governance.p7s  → links
    <keystore>/enclaves/<enclave>/permissions.{xml,p7s}

so a keystore made here serves a DDS-based ROS 2 too, and one made by sros2 serves ros2lite.
"""

from __future__ import annotations

import os
import xml.etree.ElementTree as ET
from collections.abc import Callable, Mapping
from pathlib import Path

from ros2lite.security.enclaves import (
    KEYSTORE_ENV,
    enclave_directory,
    env_domain_id,
    validate_enclave_name,
)
from ros2lite.security.errors import EnclaveError, KeystoreError
from ros2lite.security.files import make_dirs, symlink, write_file

__all__ = [
    'create_enclave',
    'create_keystore',
    'create_permission',
    'generate_artifacts',
    'is_valid_keystore',
    'keystore_from_env',
    'list_enclaves',
]

PUBLIC, PRIVATE, ENCLAVES = 'public', 'private', 'enclaves'


def is_valid_keystore(path: Path) -> bool:
    """sros2's test: both CA certificates and keys, and the signed governance, are there."""
    return all(
        (path / part).is_file()
        for part in (
            f'{PUBLIC}/permissions_ca.cert.pem',
            f'{PUBLIC}/identity_ca.cert.pem',
            f'{PRIVATE}/permissions_ca.key.pem',
            f'{PRIVATE}/identity_ca.key.pem',
            f'{ENCLAVES}/governance.p7s',
        )
    )


def _require_keystore(path: Path) -> None:
    if not is_valid_keystore(path):
        raise KeystoreError(f"'{path}' is not a valid keystore")


def _sign(keystore: Path, source: Path, target: Path) -> None:
    """Sign ``source`` with the permissions CA into ``target`` (S/MIME)."""
    from ros2lite.security import pki

    cert = pki.load_certificate(keystore / PUBLIC / 'permissions_ca.cert.pem')
    key = pki.load_private_key(keystore / PRIVATE / 'permissions_ca.key.pem')
    write_file(target, pki.sign_document(cert, key, source.read_bytes()))


def create_keystore(path: Path, env: Mapping[str, str] | None = None) -> None:
    """A new keystore at ``path``: CA, governance; refuses to touch an existing one."""
    from ros2lite.security import pki
    from ros2lite.security.permissions import governance_xml

    if is_valid_keystore(path):
        raise KeystoreError(f"keystore '{path}' already exists")
    make_dirs(path)
    public, private = make_dirs(path, PUBLIC), make_dirs(path, PRIVATE)
    enclaves = make_dirs(path, ENCLAVES)
    needed = [
        public / 'permissions_ca.cert.pem',
        public / 'identity_ca.cert.pem',
        private / 'permissions_ca.key.pem',
        private / 'identity_ca.key.pem',
    ]
    if not all(p.is_file() for p in needed):
        cert, key = pki.new_ca()
        pki.write_private_key(key, private / 'ca.key.pem')
        pki.write_certificate(cert, public / 'ca.cert.pem')
        for role in ('identity_ca', 'permissions_ca'):
            symlink('ca.cert.pem', public / f'{role}.cert.pem')
            symlink('ca.key.pem', private / f'{role}.key.pem')
    governance = enclaves / 'governance.xml'
    if not governance.is_file():
        write_file(governance, governance_xml(env_domain_id(env)))
    signed = enclaves / 'governance.p7s'
    if not signed.is_file():
        _sign(path, governance, signed)


def _write_permissions(
    keystore: Path, directory: Path, policy: ET.Element, env: Mapping[str, str] | None
) -> None:
    """permissions.xml from a one-enclave policy, valid as long as the enclave's certificate,
    and its signature permissions.p7s."""
    from ros2lite.security import pki
    from ros2lite.security.permissions import permissions_xml

    cert = pki.load_certificate(directory / 'cert.pem')
    document = permissions_xml(
        policy,
        env_domain_id(env),
        cert.not_valid_before_utc,
        cert.not_valid_after_utc,
    )
    write_file(directory / 'permissions.xml', document)
    _sign(keystore, directory / 'permissions.xml', directory / 'permissions.p7s')


def create_enclave(keystore: Path, name: str, env: Mapping[str, str] | None = None) -> Path:
    """An enclave's key, certificate, links and allow-all permissions (kept if present)."""
    from ros2lite.security import pki
    from ros2lite.security.policy import default_policy

    _require_keystore(keystore)
    validate_enclave_name(name)
    directory = enclave_directory(keystore, name)
    make_dirs(keystore, directory.relative_to(keystore))
    for public_cert in ('identity_ca.cert.pem', 'permissions_ca.cert.pem'):
        target = os.path.relpath(keystore / PUBLIC / public_cert, directory)
        symlink(target, directory / public_cert)
    symlink(
        os.path.relpath(keystore / ENCLAVES / 'governance.p7s', directory),
        directory / 'governance.p7s',
    )
    cert_path, key_path = directory / 'cert.pem', directory / 'key.pem'
    if not cert_path.is_file() or not key_path.is_file():
        ca_cert = pki.load_certificate(keystore / PUBLIC / 'identity_ca.cert.pem')
        ca_key = pki.load_private_key(keystore / PRIVATE / 'identity_ca.key.pem')
        cert, key = pki.new_identity(name, ca_cert, ca_key)
        pki.write_private_key(key, key_path)
        pki.write_certificate(cert, cert_path)
    _write_permissions(keystore, directory, default_policy(name), env)
    return directory


def list_enclaves(keystore: Path) -> list[str]:
    """Every enclave of the keystore (a directory below ``enclaves`` holding key.pem)."""
    _require_keystore(keystore)
    base = keystore / ENCLAVES
    found = {
        ('/' + key.parent.relative_to(base).as_posix()).replace('/.', '/')
        for key in base.glob('**/key.pem')
    }
    return sorted(found)


def create_permission(
    keystore: Path, name: str, policy_file: Path, env: Mapping[str, str] | None = None
) -> None:
    """Replace an enclave's permissions with what ``policy_file`` says of it (signed)."""
    from ros2lite.security.policy import load_policy, policy_for_enclave

    _require_keystore(keystore)
    validate_enclave_name(name)
    directory = enclave_directory(keystore, name)
    if not (directory / 'cert.pem').is_file():
        raise EnclaveError(f"enclave '{name}' does not exist in '{keystore}'")
    _write_permissions(keystore, directory, policy_for_enclave(load_policy(policy_file), name), env)


def keystore_from_env(env: Mapping[str, str] | None = None) -> Path:
    """``ROS_SECURITY_KEYSTORE``, for verbs whose keystore argument is optional."""
    raw = (os.environ if env is None else env).get(KEYSTORE_ENV, '')
    if not raw:
        raise KeystoreError(f"'{KEYSTORE_ENV}' isn't pointing at a valid keystore")
    return Path(raw)


def generate_artifacts(
    keystore: Path | None,
    enclaves: list[str],
    policy_files: list[Path],
    *,
    notify: Callable[[str], None] = lambda _line: None,
    env: Mapping[str, str] | None = None,
) -> None:
    """Enclaves for ``enclaves`` and every enclave of every policy, with the policies'
    permissions; a missing keystore is created first (``notify`` is told so)."""
    from ros2lite.security.policy import enclave_paths, load_policy, policy_for_enclave

    path = keystore if keystore is not None else keystore_from_env(env)
    policies = [load_policy(p) for p in policy_files]  # all checked before anything is written
    if not is_valid_keystore(path):
        notify(f'{path} is not a valid keystore, creating new keystore')
        create_keystore(path, env)
    for name in enclaves:
        create_enclave(path, name, env)
    for policy in policies:
        for name in enclave_paths(policy):
            if name not in enclaves:
                create_enclave(path, name, env)
            directory = enclave_directory(path, name)
            _write_permissions(path, directory, policy_for_enclave(policy, name), env)
