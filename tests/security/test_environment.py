"""Which identity a process takes from ROS_SECURITY_* (rcl's rules), and what the config
builders make of it."""

from __future__ import annotations

import shutil
import subprocess
from pathlib import Path

import pytest

from ros2lite.security import environment
from ros2lite.security.access import router_access
from ros2lite.security.errors import SecurityError
from ros2lite.security.keystore import create_enclave, create_keystore


@pytest.fixture(scope='module')
def keystore(tmp_path_factory: pytest.TempPathFactory) -> Path:
    root = tmp_path_factory.mktemp('env') / 'ks'
    create_keystore(root, {})
    create_enclave(root, '/robot/talker', {})
    return root


def secure(keystore: Path, **more: str) -> dict[str, str]:
    return {
        'ROS_SECURITY_ENABLE': 'true',
        'ROS_SECURITY_STRATEGY': 'Enforce',
        'ROS_SECURITY_KEYSTORE': str(keystore),
        **more,
    }


def test_off_unless_exactly_true(keystore: Path) -> None:
    assert environment.resolve({}) is None
    assert environment.resolve({**secure(keystore), 'ROS_SECURITY_ENABLE': 'True'}) is None


def test_enclave_from_override_or_argument(keystore: Path) -> None:
    found = environment.resolve(secure(keystore), enclave='/robot/talker')
    assert found is not None and found.certificate.name == 'cert.pem'
    assert found.directory == keystore / 'enclaves' / 'robot' / 'talker'
    over = environment.resolve(
        secure(keystore, ROS_SECURITY_ENCLAVE_OVERRIDE='/robot/talker'), enclave='/x'
    )
    assert over is not None and over.enclave == '/robot/talker'


def test_enforce_without_material(keystore: Path) -> None:
    with pytest.raises(SecurityError, match=r"^SECURITY ERROR: unable to find a folder matching"):
        environment.resolve(secure(keystore), enclave='/missing')
    with pytest.raises(SecurityError, match='ROS_SECURITY_KEYSTORE is not set'):
        environment.resolve({'ROS_SECURITY_ENABLE': 'true', 'ROS_SECURITY_STRATEGY': 'Enforce'})


def test_permissive_says_it_once(keystore: Path, capsys: pytest.CaptureFixture[str]) -> None:
    env = secure(keystore, ROS_SECURITY_STRATEGY='Permissive')
    assert environment.resolve(env, enclave='/nowhere') is None
    assert environment.resolve(env, enclave='/nowhere') is None
    err = capsys.readouterr().err
    assert err.count('running unsecured') == 1, err


def test_config_builders(keystore: Path) -> None:
    import json

    from ros2lite.daemon.security import secured_endpoint, session_security
    from ros2lite.transport.config import session_config

    env = secure(keystore, ROS_SECURITY_ENCLAVE_OVERRIDE='/robot/talker')
    assert secured_endpoint(env=env) == 'tls/127.0.0.1:7447'
    assert secured_endpoint(env={}) == 'tcp/127.0.0.1:7447'
    config = session_config(env=env, mode='peer', security=session_security(env))
    assert json.loads(config.get_json('mode')) == 'client'  # all traffic crosses the router
    tls = json.loads(config.get_json('transport/link/tls'))
    assert tls['enable_mtls'] is True
    assert tls['connect_certificate'].endswith('enclaves/robot/talker/cert.pem')
    assert tls['root_ca_certificate'].endswith('identity_ca.cert.pem')


def test_permissions_of_another_domain(keystore: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """The keystore's permissions cover domain 0: a process in 177 would be denied all by
    the router. Enforce refuses in one line; Permissive warns once and goes on."""
    env = secure(keystore, ROS_DOMAIN_ID='177')
    with pytest.raises(SecurityError) as caught:
        environment.resolve(env, enclave='/robot/talker')
    assert str(caught.value) == (
        'SECURITY ERROR: permissions of enclave /robot/talker cover domain 0, not 177 '
        '(ROS_SECURITY_STRATEGY=Enforce)'
    )
    assert environment.resolve(secure(keystore, ROS_DOMAIN_ID='0'), enclave='/robot/talker')
    permissive = {**env, 'ROS_SECURITY_STRATEGY': 'Permissive'}
    for _ in range(2):
        found = environment.resolve(permissive, enclave='/robot/talker')
        assert found is not None and found.enclave == '/robot/talker'
    warnings = [line for line in capsys.readouterr().err.splitlines() if 'SECURITY' in line]
    assert len(warnings) == 1, warnings
    assert 'permissions of enclave /robot/talker cover domain 0, not 177' in warnings[0]


def replace_certificate(
    keystore: Path, enclave: str, common_name: str, *, expired: bool = False
) -> None:
    """Give `enclave` a certificate the keystore's CA signed for `common_name`, valid now
    or expired a day ago."""
    import datetime

    from cryptography import x509
    from cryptography.hazmat.primitives import hashes
    from cryptography.hazmat.primitives.asymmetric import ec

    from ros2lite.security import pki

    directory = keystore / 'enclaves' / enclave.strip('/')
    ca = pki.load_certificate(keystore / 'public' / 'ca.cert.pem')
    ca_key = pki.load_private_key(keystore / 'private' / 'ca.key.pem')
    key = ec.generate_private_key(ec.SECP256R1())
    now = datetime.datetime.now(datetime.timezone.utc)
    end = now - datetime.timedelta(days=1) if expired else now + datetime.timedelta(days=1)
    cert = (
        x509.CertificateBuilder()
        .issuer_name(ca.subject)
        .subject_name(x509.Name([x509.NameAttribute(x509.oid.NameOID.COMMON_NAME, common_name)]))
        .serial_number(x509.random_serial_number())
        .not_valid_before(end - datetime.timedelta(days=30))
        .not_valid_after(end)
        .public_key(key.public_key())
        .sign(ca_key, hashes.SHA256())
    )
    (directory / 'cert.pem').unlink()
    (directory / 'key.pem').unlink()
    pki.write_certificate(cert, directory / 'cert.pem')
    pki.write_private_key(key, directory / 'key.pem')


def test_certificates_the_router_would_refuse(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """Another enclave's certificate, an expired one, one from another CA: each refused in
    one line under Enforce, said once under Permissive."""
    from ros2lite.security import pki

    root = tmp_path / 'ks'
    create_keystore(root, {})
    for name in ('/a', '/b', '/c'):
        create_enclave(root, name, {})
    replace_certificate(root, '/a', '/wrong')
    replace_certificate(root, '/b', '/b', expired=True)
    other_ca, other_key = pki.new_ca()
    cert, key = pki.new_identity('/c', other_ca, other_key)
    for name in ('cert.pem', 'key.pem'):
        (root / 'enclaves' / 'c' / name).unlink()
    pki.write_certificate(cert, root / 'enclaves' / 'c' / 'cert.pem')
    pki.write_private_key(key, root / 'enclaves' / 'c' / 'key.pem')
    expected = {
        '/a': 'the certificate of enclave /a names CN=/wrong, not /a',
        '/b': 'the certificate of enclave /b expired on ',
        '/c': "the certificate of enclave /c is not issued by the keystore's identity CA",
    }
    for enclave, reason in expected.items():
        with pytest.raises(SecurityError) as caught:
            environment.resolve(secure(root), enclave=enclave)
        message = str(caught.value)
        assert message.startswith(f'SECURITY ERROR: {reason}'), message
        assert message.endswith('(ROS_SECURITY_STRATEGY=Enforce)') and '\n' not in message
        permissive = secure(root, ROS_SECURITY_STRATEGY='Permissive')
        assert environment.resolve(permissive, enclave=enclave) is not None
        assert reason in capsys.readouterr().err


def test_unsigned_or_tampered_documents(tmp_path: Path) -> None:
    """R-S13: permissions or governance changed after the permissions CA signed them (or a
    signature that is missing) are refused in one line under Enforce."""
    root = tmp_path / 'ks'
    create_keystore(root, {})
    create_enclave(root, '/p', {})
    permissions = root / 'enclaves' / 'p' / 'permissions.xml'
    original = permissions.read_bytes()
    permissions.write_bytes(original.replace(b'<topic>rt/*</topic>', b'<topic>rt/**</topic>'))
    with pytest.raises(SecurityError) as caught:
        environment.resolve(secure(root), enclave='/p')
    assert str(caught.value) == (
        'SECURITY ERROR: permissions of enclave /p: permissions.xml does not match its '
        'signature permissions.p7s by the permissions CA (ROS_SECURITY_STRATEGY=Enforce)'
    )
    permissions.write_bytes(original)
    assert environment.resolve(secure(root), enclave='/p') is not None
    (root / 'enclaves' / 'p' / 'permissions.p7s').unlink()
    with pytest.raises(SecurityError, match=r'permissions.p7s \(its signature\) is missing'):
        environment.resolve(secure(root), enclave='/p')
    create_enclave(root, '/p', {})  # signs them again
    governance = root / 'enclaves' / 'governance.xml'
    governance.write_bytes(governance.read_bytes().replace(b'ENCRYPT', b'NONE'))
    with pytest.raises(SecurityError, match=r'governance of keystore .*: governance.xml does not'):
        environment.resolve(secure(root), enclave='/p')


def _resign_as_enclave(directory: Path, document: str) -> None:
    """What R5-S1 did: the enclave's own key signs its edited document, with openssl (in
    sros2's default keystore the enclave's certificate chains to the permissions CA)."""
    subprocess.run(
        [
            'openssl',
            'smime',
            '-sign',
            '-text',
            '-in',
            str(directory / f'{document}.xml'),
            '-out',
            str(directory / f'{document}.p7s'),
            '-signer',
            str(directory / 'cert.pem'),
            '-inkey',
            str(directory / 'key.pem'),
        ],
        check=True,
        capture_output=True,
    )


@pytest.mark.skipif(shutil.which('openssl') is None, reason='needs the openssl command')
def test_permissions_signed_by_anything_but_the_permissions_ca_are_refused(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """R5-S1: an enclave that grants itself a topic and re-signs the document with its own
    key is refused under Enforce and warned about under Permissive, as DDS Security asks for
    the permissions CA's own signature."""
    root = tmp_path / 'ks'
    create_keystore(root, {})
    create_enclave(root, '/tl/evil', {})
    directory = root / 'enclaves' / 'tl' / 'evil'
    permissions = directory / 'permissions.xml'
    permissions.write_bytes(
        permissions.read_bytes().replace(b'<topic>rt/*</topic>', b'<topic>rt/chatter</topic>')
    )
    _resign_as_enclave(directory, 'permissions')
    with pytest.raises(SecurityError) as caught:
        environment.resolve(secure(root), enclave='/tl/evil')
    assert str(caught.value) == (
        'SECURITY ERROR: permissions of enclave /tl/evil: permissions.p7s is signed by '
        'CN=/tl/evil, not by the permissions CA (ROS_SECURITY_STRATEGY=Enforce)'
    )
    permissive = secure(root, ROS_SECURITY_STRATEGY='Permissive')
    assert environment.resolve(permissive, enclave='/tl/evil') is not None
    assert 'permissions.p7s is signed by CN=/tl/evil' in capsys.readouterr().err
    # the router's access control drops that enclave too
    access = router_access(root)
    assert [s.common_name for s in access.subjects] == []
    assert any('signed by CN=/tl/evil, not by the permissions CA' in w for w in access.warnings)
    # and the document the CA signs again is obeyed again
    create_enclave(root, '/tl/evil', {})
    assert environment.resolve(secure(root), enclave='/tl/evil') is not None
    # the governance, re-signed by an enclave, is refused the same way
    shutil.copy(root / 'enclaves' / 'governance.xml', tmp_path / 'governance.xml')
    for name in ('cert.pem', 'key.pem'):
        shutil.copy(directory / name, tmp_path / name)
    _resign_as_enclave(tmp_path, 'governance')
    (root / 'enclaves' / 'governance.p7s').write_bytes((tmp_path / 'governance.p7s').read_bytes())
    with pytest.raises(SecurityError, match=r'governance.p7s is signed by CN=/tl/evil'):
        environment.resolve(secure(root), enclave='/tl/evil')
