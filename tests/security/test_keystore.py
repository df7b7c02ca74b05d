"""Keystores made by `ros2lite security` verbs, checked from the outside with openssl: the
chain, that each key matches its certificate, and the S/MIME signatures of governance and
permissions (what a DDS-based ROS 2 would check)."""

from __future__ import annotations

import shutil
import subprocess
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest

pytestmark = pytest.mark.skipif(shutil.which('openssl') is None, reason='needs openssl')


def openssl(*args: str, cwd: Path) -> str:
    done = subprocess.run(['openssl', *args], cwd=cwd, capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    return done.stdout + done.stderr


@pytest.fixture(scope='module')
def keystore(tmp_path_factory: pytest.TempPathFactory) -> Path:
    from ros2lite.cli.main import main

    root = tmp_path_factory.mktemp('ks') / 'keystore'
    assert main(['security', 'create_keystore', str(root)]) == 0
    assert main(['security', 'create_enclave', str(root), '/talker_listener/talker']) == 0
    assert main(['security', 'create_key', str(root), '/talker_listener/listener']) == 0
    return root


def test_layout(keystore: Path) -> None:
    assert sorted(p.name for p in (keystore / 'public').iterdir()) == [
        'ca.cert.pem',
        'identity_ca.cert.pem',
        'permissions_ca.cert.pem',
    ]
    assert (keystore / 'public' / 'identity_ca.cert.pem').is_symlink()
    assert sorted(p.name for p in (keystore / 'private').iterdir()) == [
        'ca.key.pem',
        'identity_ca.key.pem',
        'permissions_ca.key.pem',
    ]
    assert (keystore / 'private' / 'ca.key.pem').stat().st_mode & 0o077 == 0
    enclave = keystore / 'enclaves' / 'talker_listener' / 'talker'
    assert sorted(p.name for p in enclave.iterdir()) == [
        'cert.pem',
        'governance.p7s',
        'identity_ca.cert.pem',
        'key.pem',
        'permissions.p7s',
        'permissions.xml',
        'permissions_ca.cert.pem',
    ]
    assert (enclave / 'key.pem').stat().st_mode & 0o077 == 0
    assert (enclave / 'governance.p7s').resolve() == (keystore / 'enclaves/governance.p7s')


def test_certificates_chain_and_keys_match(keystore: Path) -> None:
    enclave = keystore / 'enclaves' / 'talker_listener' / 'talker'
    assert 'cert.pem: OK' in openssl(
        'verify', '-CAfile', 'identity_ca.cert.pem', 'cert.pem', cwd=enclave
    )
    subject = openssl('x509', '-in', 'cert.pem', '-noout', '-subject', '-issuer', cwd=enclave)
    assert 'CN = /talker_listener/talker' in subject and 'CN = sros2CA' in subject
    text = openssl('x509', '-in', '../../../public/ca.cert.pem', '-noout', '-text', cwd=enclave)
    assert 'CA:TRUE' in text and 'prime256v1' in text and 'ecdsa-with-SHA256' in text
    for directory, cert, key in (
        (enclave, 'cert.pem', 'key.pem'),
        (keystore, 'public/ca.cert.pem', 'private/ca.key.pem'),
    ):
        from_cert = openssl('x509', '-in', cert, '-noout', '-pubkey', cwd=directory)
        from_key = openssl('pkey', '-in', key, '-pubout', cwd=directory)
        assert from_cert == from_key


@pytest.mark.parametrize('document', ['governance', 'talker_listener/talker/permissions'])
def test_smime_signatures(keystore: Path, document: str) -> None:
    enclaves = keystore / 'enclaves'
    out = openssl(
        'smime',
        '-verify',
        '-in',
        f'{document}.p7s',
        '-CAfile',
        '../public/permissions_ca.cert.pem',
        '-text',
        cwd=enclaves,
    )
    assert 'Verification successful' in out
    signed = out.replace('Verification successful', '').replace('\r\n', '\n').strip()
    assert signed == (enclaves / f'{document}.xml').read_text().strip()
    head = (enclaves / f'{document}.p7s').read_text().splitlines()[:2]
    assert head[0] == 'MIME-Version: 1.0'
    assert head[1].startswith(
        'Content-Type: multipart/signed; protocol="application/x-pkcs7-'
        'signature"; micalg="sha-256";'
    )


def test_tampered_permissions_fail_verification(keystore: Path, tmp_path: Path) -> None:
    signed = (keystore / 'enclaves/talker_listener/talker/permissions.p7s').read_text()
    forged = tmp_path / 'forged.p7s'
    forged.write_text(signed.replace('<topic>rt/*</topic>', '<topic>rt/x</topic>', 1))
    done = subprocess.run(
        [
            'openssl',
            'smime',
            '-verify',
            '-in',
            str(forged),
            '-CAfile',
            str(keystore / 'public/ca.cert.pem'),
            '-out',
            '/dev/null',
        ],
        capture_output=True,
        text=True,
    )
    assert done.returncode != 0


def test_list_enclaves(keystore: Path, run: Callable[..., Any]) -> None:
    result = run('security', 'list_enclaves', str(keystore))
    assert (result.code, result.out) == (0, '/talker_listener/listener\n/talker_listener/talker\n')


def test_errors_are_one_line(keystore: Path, tmp_path: Path, run: Callable[..., Any]) -> None:
    again = run('security', 'create_keystore', str(keystore))
    assert again.code == 1
    assert again.err == f"Unable to create keystore: keystore '{keystore}' already exists\n"
    bad = run('security', 'create_enclave', str(keystore), 'no/leading/slash')
    assert bad.code == 1 and bad.err.startswith("Unable to create enclave: 'no/leading/slash'")
    missing = run('security', 'list_enclaves', str(tmp_path / 'none'))
    assert (
        missing.err == f"Unable to list enclaves: '{tmp_path / 'none'}' is not a valid keystore\n"
    )
    # re-creating an enclave keeps its key (sros2 does too)
    key = (keystore / 'enclaves/talker_listener/talker/key.pem').read_bytes()
    assert run('security', 'create_enclave', str(keystore), '/talker_listener/talker').code == 0
    assert (keystore / 'enclaves/talker_listener/talker/key.pem').read_bytes() == key


def test_no_write_through_a_symlink(tmp_path: Path, run: Callable[..., Any]) -> None:
    """A key planted as a symlink elsewhere is refused, and the target stays untouched."""
    root = tmp_path / 'ks'
    assert run('security', 'create_keystore', str(root)).code == 0
    victim = tmp_path / 'victim'
    victim.write_text('precious')
    enclave = root / 'enclaves' / 'e'
    enclave.mkdir()
    (enclave / 'key.pem').symlink_to(victim)
    result = run('security', 'create_enclave', str(root), '/e')
    assert result.code == 1 and 'symlink' in result.err, result.err
    assert victim.read_text() == 'precious'
