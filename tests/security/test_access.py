"""Enclave permissions → router access rules, and the key expressions they stand on."""

from __future__ import annotations

from pathlib import Path

import pytest

from ros2lite.security.access import keys_for_name, router_access, token_topic
from ros2lite.security.keystore import create_enclave, create_keystore, create_permission


@pytest.mark.parametrize(
    ('name', 'allow', 'key'),
    [
        ('/chatter', True, '0/chatter/*/*'),
        ('/robot/chatter', True, '0/robot/chatter/*/*'),
        ('/*', True, '0/*/**/*/*'),
        ('/robot/*', True, '0/robot/*/**/*/*'),
        ('/chat*', True, '0/chat$*/*/*'),
        ('/chat*', False, '0/*/**/*/*'),
    ],
)
def test_keys_for_name(name: str, allow: bool, key: str) -> None:
    assert keys_for_name(name, 0, allow=allow) == key


def test_rules_follow_permissions(tmp_path: Path) -> None:
    env = {'ROS_DOMAIN_ID': '5'}
    keystore = tmp_path / 'ks'
    create_keystore(keystore, env)
    create_enclave(keystore, '/open', env)
    create_enclave(keystore, '/narrow', env)
    policy = tmp_path / 'p.xml'
    policy.write_text(
        '<policy version="0.2.0"><enclaves><enclave path="/narrow"><profiles>'
        '<profile ns="/" node="n"><topics subscribe="ALLOW"><topic>chatter</topic></topics>'
        '<services request="ALLOW"><service>add</service></services>'
        '<topics publish="DENY"><topic>chatter</topic></topics>'
        '</profile></profiles></enclave></enclaves></policy>'
    )
    create_permission(keystore, '/narrow', policy, env)
    access = router_access(keystore)
    assert access.warnings == []
    by_cn = {s.common_name: s for s in access.subjects}
    assert set(by_cn) == {'/open', '/narrow'}
    rules = {r.id: r for r in access.rules}
    narrow = [rules[i] for i in by_cn['/narrow'].rules]

    def keys(allow: bool, flow: str, message: str) -> set[str]:
        return {
            k
            for r in narrow
            if r.allow == allow and r.flow == flow and message in r.messages
            for k in r.key_exprs
        }

    assert keys(True, 'ingress', 'declare_subscriber') == {'5/chatter/*/*'}
    assert keys(True, 'egress', 'put') == {'5/chatter/*/*'}
    assert keys(True, 'ingress', 'put') == set()  # may not publish it
    assert keys(False, 'ingress', 'put') == {'5/chatter/*/*'}  # and a DENY says so too
    assert keys(True, 'ingress', 'query') >= {'5/add/*/*'}
    assert keys(True, 'egress', 'reply') >= {'5/add/*/*'}
    assert keys(True, 'ingress', 'liveliness_token') == {
        # its own graph tokens, named after it, in its domain only, for what it may do
        '@ros2_lv/5/*/*/*/NN/%narrow/*/*',
        '@ros2_lv/5/*/*/*/MS/%narrow/*/*/%chatter/**',
        '@ros2_lv/5/*/*/*/SC/%narrow/*/*/%add/**',
        '5/chatter/*/*/@adv/sub/**',  # its TRANSIENT_LOCAL subscriber's
    }
    assert '@ros2_lv/5/*/*/*/MP/%narrow/*/*/%chatter/**' in keys(
        False, 'ingress', 'liveliness_token'
    )


@pytest.mark.parametrize(
    ('name', 'allow', 'chunk'),
    [
        ('/chatter', True, '%chatter'),
        ('/robot/chatter', True, '%robot%chatter'),
        ('/*', True, '%$*'),
        ('/robot/*', True, '%robot%$*'),
        ('/chat*', True, '%chat$*'),
        ('/chat*/x', False, '%$*'),
    ],
)
def test_token_topic(name: str, allow: bool, chunk: str) -> None:
    assert token_topic(name, allow=allow) == chunk


def signed(keystore: Path, enclave: str, document: bytes) -> None:
    """Write an enclave's permissions, signed by the keystore's permissions CA."""
    from ros2lite.security import pki

    directory = keystore / 'enclaves' / enclave.strip('/')
    cert = pki.load_certificate(keystore / 'public' / 'permissions_ca.cert.pem')
    key = pki.load_private_key(keystore / 'private' / 'permissions_ca.key.pem')
    (directory / 'permissions.xml').write_bytes(document)
    (directory / 'permissions.p7s').write_bytes(pki.sign_document(cert, key, document))


def test_bad_or_foreign_grants_are_left_out(tmp_path: Path) -> None:
    keystore = tmp_path / 'ks'
    create_keystore(keystore, {})
    create_enclave(keystore, '/a', {})
    create_enclave(keystore, '/b', {})
    create_enclave(keystore, '/c', {})
    # /b's file grants to someone else; /c's is not XML (both signed by the CA)
    text = (keystore / 'enclaves/b/permissions.xml').read_bytes()
    signed(keystore, '/b', text.replace(b'CN=/b', b'CN=/a'))
    signed(keystore, '/c', b'<dds')
    access = router_access(keystore)
    assert [s.common_name for s in access.subjects] == ['/a']
    assert any(w.startswith('/b: its permissions grant nothing') for w in access.warnings)
    assert any(w.startswith('/c: ignored') for w in access.warnings)


def test_tampered_permissions_are_denied(tmp_path: Path) -> None:
    """R-S13: permissions.xml edited after signing (an enclave granting itself a topic) is
    not obeyed: its permissions.p7s no longer verifies against the permissions CA."""
    keystore = tmp_path / 'ks'
    create_keystore(keystore, {})
    create_enclave(keystore, '/ok', {})
    create_enclave(keystore, '/other', {})
    path = keystore / 'enclaves/other/permissions.xml'
    path.write_bytes(path.read_bytes().replace(b'rt/*', b'rt/*x', 1))
    access = router_access(keystore)
    assert [s.common_name for s in access.subjects] == ['/ok']
    assert access.warnings == [
        '/other: ignored (permissions of enclave /other: permissions.xml does not match its '
        'signature permissions.p7s by the permissions CA)'
    ]
