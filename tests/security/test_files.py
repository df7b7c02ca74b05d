"""Private keys are written only as new files of ours (R-S14/S15): a file or directory
another user planted where a key goes is refused, never written into."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from ros2lite.security.errors import KeystoreError
from ros2lite.security.keystore import create_enclave, create_keystore

NOBODY = 65534
needs_root = pytest.mark.skipif(os.geteuid() != 0, reason='needs root to plant foreign files')


def plant(path: Path, mode: int = 0o666) -> None:
    """An empty file at `path` owned by another user (as `nobody` would leave it)."""
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_bytes(b'')
    os.chown(path, NOBODY, NOBODY)
    path.chmod(mode)


@needs_root
def test_foreign_ca_key_file_refused(tmp_path: Path) -> None:
    keystore = tmp_path / 'ks'
    plant(keystore / 'private' / 'ca.key.pem')
    with pytest.raises(KeystoreError) as caught:
        create_keystore(keystore, {})
    assert str(caught.value) == (
        f"refusing to write the private key '{keystore}/private/ca.key.pem': it exists and "
        f'belongs to another user (uid {NOBODY})'
    )
    assert (keystore / 'private' / 'ca.key.pem').read_bytes() == b''  # nothing written in


@needs_root
def test_foreign_directory_refused(tmp_path: Path) -> None:
    keystore = tmp_path / 'ks'
    (keystore / 'private').mkdir(parents=True)
    os.chown(keystore / 'private', NOBODY, NOBODY)
    with pytest.raises(KeystoreError, match='its directory belongs to another user'):
        create_keystore(keystore, {})
    assert not (keystore / 'private' / 'ca.key.pem').exists()


@needs_root
def test_foreign_enclave_key_refused(tmp_path: Path) -> None:
    keystore = tmp_path / 'ks'
    create_keystore(keystore, {})
    shared = keystore / 'enclaves' / 'shared'
    shared.mkdir(mode=0o1777)
    plant(shared / 'key.pem')
    with pytest.raises(KeystoreError, match=r"private key '.*/shared/key\.pem': it exists"):
        create_enclave(keystore, '/shared', {})
    assert (shared / 'key.pem').stat().st_uid == NOBODY and not (shared / 'cert.pem').exists()


def test_keys_are_new_private_files(tmp_path: Path) -> None:
    """A stale key of ours (0644, say) is replaced by a new 0600 file, not rewritten."""
    keystore = tmp_path / 'ks'
    create_keystore(keystore, {})
    directory = keystore / 'enclaves' / 'e'
    directory.mkdir()
    stale = directory / 'key.pem'
    stale.write_bytes(b'stale')
    stale.chmod(0o644)
    os.link(stale, tmp_path / 'other-name')  # another name for the old file
    create_enclave(keystore, '/e', {})
    assert stale.stat().st_mode & 0o777 == 0o600 and stale.read_bytes().startswith(b'-----BEGIN')
    assert (tmp_path / 'other-name').read_bytes() == b'stale'  # a new file, not written in
    assert (keystore / 'private' / 'ca.key.pem').stat().st_mode & 0o777 == 0o600
