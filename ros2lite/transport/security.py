"""Security on the Zenoh side: TLS with mutual authentication, and the router's access control.

The library (:mod:`ros2lite.security`) decides *what* — which certificate, which CA, which
rules from which permissions; this module only writes it into a ``zenoh.Config``:

* ``transport/link/tls``: the keystore's identity CA as ``root_ca_certificate``, the enclave's
  certificate and key for both listening and connecting, ``enable_mtls`` (a peer without a
  certificate from that CA is refused during the handshake) and no host-name check (sros2
  certificates name enclaves, not hosts);
* ``access_control``: ``default_permission: deny``, one subject per enclave by
  ``cert_common_names``, the rules as given (key expressions canonised here).
"""

from __future__ import annotations

import json
from typing import TYPE_CHECKING

import zenoh

from ros2lite.transport.errors import ConfigError, zerror_message

if TYPE_CHECKING:
    from ros2lite.security.access import AccessControl
    from ros2lite.security.environment import Identity

__all__ = ['apply_access_control', 'apply_tls', 'is_tls_endpoint']


def is_tls_endpoint(endpoint: str) -> bool:
    """Does the endpoint use the TLS link (``tls/host:port``)?"""
    return endpoint.strip().partition('/')[0] == 'tls'


def _insert(config: zenoh.Config, key: str, value: object, what: str) -> None:
    try:
        config.insert_json5(key, json.dumps(value))
    except zenoh.ZError as exc:
        raise ConfigError(f'{what}: cannot set {key}: {zerror_message(exc)}') from None


def apply_tls(config: zenoh.Config, identity: Identity) -> None:
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
