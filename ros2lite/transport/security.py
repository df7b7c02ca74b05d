"""Security on the Zenoh side: TLS with mutual authentication, and the router's access control.

The library (:mod:`ros2lite.security`) decides *what* — which certificate, which CA, which
rules from which permissions — and its callers hand that down as a :class:`Security` value
(this package imports nothing from ``ros2lite.security``); this module only writes it into a
``zenoh.Config``:

* ``transport/link/tls``: the keystore's identity CA as ``root_ca_certificate``, the enclave's
  certificate and key for both listening and connecting, ``enable_mtls`` (a peer without a
  certificate from that CA is refused during the handshake) and no host-name check (sros2
  certificates name enclaves, not hosts);
* ``access_control``: ``default_permission: deny``, one subject per enclave by
  ``cert_common_names``, the rules as given (key expressions canonised here).
"""

from __future__ import annotations

import json
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Protocol

import zenoh

from ros2lite.transport.errors import ConfigError, zerror_message

__all__ = [
    'UNSECURED',
    'AccessControl',
    'AccessRule',
    'AccessSubject',
    'Credentials',
    'Security',
    'apply_access_control',
    'apply_tls',
    'is_tls_endpoint',
]


class Credentials(Protocol):
    """One enclave's TLS material: whom to trust and who we are."""

    @property
    def enclave(self) -> str: ...
    @property
    def ca_certificate(self) -> Path: ...
    @property
    def certificate(self) -> Path: ...
    @property
    def private_key(self) -> Path: ...


class AccessRule(Protocol):
    """One Zenoh ACL rule (key expressions are canonised here)."""

    @property
    def id(self) -> str: ...
    @property
    def allow(self) -> bool: ...
    @property
    def flow(self) -> str: ...
    @property
    def messages(self) -> Sequence[str]: ...
    @property
    def key_exprs(self) -> Sequence[str]: ...


class AccessSubject(Protocol):
    """One enclave as the router knows it: by its certificate's common name."""

    @property
    def id(self) -> str: ...
    @property
    def common_name(self) -> str: ...
    @property
    def rules(self) -> Sequence[str]: ...


class AccessControl(Protocol):
    """What a router enforces."""

    @property
    def rules(self) -> Sequence[AccessRule]: ...
    @property
    def subjects(self) -> Sequence[AccessSubject]: ...


@dataclass(frozen=True)
class Security:
    """Security as a session or router config needs it, decided outside transport.

    ``credentials``: this process's (or the router's) enclave, None when it runs unsecured;
    ``refuse_plain``: why a link that is not TLS is refused (``''``: it is not refused);
    ``access``: a router's access control (None for sessions).
    """

    credentials: Credentials | None = None
    refuse_plain: str = ''
    access: AccessControl | None = None

    @property
    def secure_default(self) -> bool:
        """Is the default router endpoint the TLS one?"""
        return self.credentials is not None or bool(self.refuse_plain)


UNSECURED = Security()


def is_tls_endpoint(endpoint: str) -> bool:
    """Does the endpoint use the TLS link (``tls/host:port``)?"""
    return endpoint.strip().partition('/')[0] == 'tls'


def _insert(config: zenoh.Config, key: str, value: object, what: str) -> None:
    try:
        config.insert_json5(key, json.dumps(value))
    except zenoh.ZError as exc:
        raise ConfigError(f'{what}: cannot set {key}: {zerror_message(exc)}') from None


def apply_tls(config: zenoh.Config, identity: Credentials) -> None:
    """Make every TLS link of ``config`` authenticate both ends with ``identity``."""
    what = f'security (enclave {identity.enclave})'
    tls = {
        'root_ca_certificate': str(identity.ca_certificate),
        'listen_private_key': str(identity.private_key),
        'listen_certificate': str(identity.certificate),
        'connect_private_key': str(identity.private_key),
        'connect_certificate': str(identity.certificate),
        'enable_mtls': True,
        'verify_name_on_connect': False,
    }
    for key, value in tls.items():
        _insert(config, f'transport/link/tls/{key}', value, what)


def _canon(key_expr: str) -> str:
    try:
        return str(zenoh.KeyExpr.autocanonize(key_expr))
    except zenoh.ZError as exc:
        raise ConfigError(f'access control: bad key expression {key_expr!r}: {exc}') from None


def apply_access_control(config: zenoh.Config, access: AccessControl) -> None:
    """Turn on access control, deny by default, and allow (or deny) what ``access`` says."""
    rules = [
        {
            'id': rule.id,
            'permission': 'allow' if rule.allow else 'deny',
            'flows': [rule.flow],
            'messages': list(rule.messages),
            'key_exprs': sorted({_canon(k) for k in rule.key_exprs}),
        }
        for rule in access.rules
    ]
    subjects = [{'id': s.id, 'cert_common_names': [s.common_name]} for s in access.subjects]
    policies = [{'rules': list(s.rules), 'subjects': [s.id]} for s in access.subjects if s.rules]
    _insert(
        config,
        'access_control',
        {
            'enabled': True,
            'default_permission': 'deny',
            'rules': rules,
            'subjects': subjects,
            'policies': policies,
        },
        'access control',
    )
