"""Which security material a process uses, decided from the variables ROS users set.

rcl's rules, kept as they are so the same shell works for ROS 2 and ros2lite:

* ``ROS_SECURITY_ENABLE`` must be exactly ``true`` for anything to happen;
* ``ROS_SECURITY_STRATEGY=Enforce`` makes missing material fatal, anything else is
  Permissive (run unsecured, and say so once);
* the enclave is ``ROS_SECURITY_ENCLAVE_OVERRIDE`` if set, else the process's own
  (``--ros-args --enclave``, registered with :func:`use_enclave`), else ``/``;
* its directory is ``$ROS_SECURITY_KEYSTORE/enclaves/<enclave>``.

Material that is there but would be refused or ignored by the router (a certificate for
another enclave, expired, or from another CA; governance or permissions whose signature
does not verify; permissions for another ``ROS_DOMAIN_ID``) is named in one line by
:func:`enclave_problems`, the same words for every node and verb: fatal under Enforce, a
warning under Permissive.  Every session and router config passes through here.

On Zenoh an identity is what TLS needs: the keystore's identity CA (to check the other end),
and the enclave's certificate and key (to be checked).  The router has an enclave of its own
(``ROS2LITE_ROUTER_ENCLAVE``, default ``/zenohd`` as rmw_zenoh's tools name it), created on
first use when the keystore's CA key is at hand.
"""

from __future__ import annotations

import datetime
import os
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path

from ros2lite.security.enclaves import (
    KEYSTORE_ENV,
    enclave_directory,
    env_domain_id,
    validate_enclave_name,
)
from ros2lite.security.errors import EnclaveError, SecurityError

__all__ = [
    'DEFAULT_ROUTER_ENCLAVE',
    'ENABLE_ENV',
    'KEYSTORE_ENV',
    'OVERRIDE_ENV',
    'ROUTER_ENCLAVE_ENV',
    'STRATEGY_ENV',
    'Identity',
    'announced_enclave',
    'enclave_directory',
    'enclave_problems',
    'enforced',
    'process_enclave',
    'resolve',
    'router_identity',
    'security_enabled',
    'use_enclave',
    'validate_enclave_name',
]

ENABLE_ENV = 'ROS_SECURITY_ENABLE'
STRATEGY_ENV = 'ROS_SECURITY_STRATEGY'
OVERRIDE_ENV = 'ROS_SECURITY_ENCLAVE_OVERRIDE'
ROUTER_ENCLAVE_ENV = 'ROS2LITE_ROUTER_ENCLAVE'
DEFAULT_ROUTER_ENCLAVE = '/zenohd'

CA_FILE = 'identity_ca.cert.pem'
CERT_FILE = 'cert.pem'
KEY_FILE = 'key.pem'

# the process's enclave, as rcl takes it from `--ros-args --enclave` (None: '/')
_process_enclave: str | None = None
# Permissive fall-backs already reported, so a process says it once
_reported: set[str] = set()


@dataclass(frozen=True)
class Identity:
    """One enclave's TLS material: whom to trust and who we are."""

    enclave: str
    keystore: Path
    directory: Path
    ca_certificate: Path
    certificate: Path
    private_key: Path


def _env(env: Mapping[str, str] | None) -> Mapping[str, str]:
    return os.environ if env is None else env


def security_enabled(env: Mapping[str, str] | None = None) -> bool:
    """``ROS_SECURITY_ENABLE`` is exactly ``true`` (rcl compares it so)."""
    return _env(env).get(ENABLE_ENV, '') == 'true'


def enforced(env: Mapping[str, str] | None = None) -> bool:
    """Security is on and ``ROS_SECURITY_STRATEGY`` is exactly ``Enforce``."""
    return security_enabled(env) and _env(env).get(STRATEGY_ENV, '') == 'Enforce'


def use_enclave(name: str | None) -> None:
    """Record this process's enclave (``--ros-args --enclave``); None forgets it."""
    global _process_enclave
    if name is not None:
        validate_enclave_name(name)
    _process_enclave = name


def process_enclave() -> str:
    """The enclave this process declared, ``/`` when none was (rcl's default)."""
    return _process_enclave or '/'


def announced_enclave(enclave: str | None, env: Mapping[str, str] | None = None) -> str:
    """The enclave a context names in its graph tokens: with security on, the one whose
    certificate it shows (``ROS_SECURITY_ENCLAVE_OVERRIDE`` wins), so the router can bind
    tokens to the enclave that declares them; else ``enclave`` (``--enclave``, default
    ``/``), as rmw_zenoh does."""
    environ = _env(env)
    override = environ.get(OVERRIDE_ENV, '')
    if security_enabled(environ) and override:
        try:
            validate_enclave_name(override)
        except EnclaveError:
            return enclave or '/'  # resolve() says why, once
        return override
    return enclave or '/'


def _identity(keystore: Path, enclave: str) -> Identity | str:
    """The enclave's identity, or why it cannot be had (one phrase)."""
    directory = enclave_directory(keystore, enclave)
    if not directory.is_dir():
        return f"unable to find a folder matching the name '{enclave}' in '{keystore}'"
    files = {name: directory / name for name in (CA_FILE, CERT_FILE, KEY_FILE)}
    missing = [name for name, path in files.items() if not path.is_file()]
    if missing:
        return f"enclave '{enclave}' in '{keystore}' lacks {', '.join(missing)}"
    return Identity(
        enclave,
        keystore,
        directory,
        files[CA_FILE],
        files[CERT_FILE],
        files[KEY_FILE],
    )


def _fallback(reason: str) -> None:
    """Permissive: carry on unsecured, and say so once per reason."""
    _warn_once(reason, f'SECURITY: {reason}; running unsecured ({STRATEGY_ENV} is not Enforce)')


def _domains_phrase(domains: list[int]) -> str:
    if not domains:
        return 'no domain'
    listed = ', '.join(str(d) for d in domains)
    return f'domain {listed}' if len(domains) == 1 else f'domains {listed}'


def enclave_problems(
    identity: Identity, domain: int | None, now: datetime.datetime | None = None
) -> list[str]:
    """Why the router would refuse or ignore this enclave, one phrase each (empty: none):
    its certificate (issued by the keystore's identity CA, naming the enclave, valid now),
    the keystore's governance and the enclave's permissions (signed by the permissions CA),
    a grant for the enclave valid now, covering ``domain`` unless None (the router's)."""
    from ros2lite.security import pki
    from ros2lite.security.permissions import parse_permissions

    when = now or datetime.datetime.now(datetime.timezone.utc)
    enclave = identity.enclave
    problems: list[str] = []
    try:
        problem = pki.certificate_problem(
            pki.load_certificate(identity.certificate),
            pki.load_certificate(identity.ca_certificate),
            enclave,
            when,
        )
    except SecurityError as exc:
        problem = str(exc)
    if problem:
        problems.append(problem)
    permissions_ca = identity.keystore / 'public' / 'permissions_ca.cert.pem'
    try:
        pki.read_signed(
            identity.keystore / 'enclaves' / 'governance.xml',
            identity.keystore / 'enclaves' / 'governance.p7s',
            permissions_ca,
            f'the governance of keystore {identity.keystore}',
        )
    except SecurityError as exc:
        problems.append(str(exc))
    what = f'permissions of enclave {enclave}'
    path = identity.directory / 'permissions.xml'
    try:
        document = pki.read_signed(
            path, identity.directory / 'permissions.p7s', permissions_ca, what
        )
        grants = parse_permissions(document, str(path))
    except SecurityError as exc:
        return [*problems, str(exc)]
    grant = next((g for g in grants if g.common_name == enclave), None)
    if grant is None:
        return [*problems, f'{what} grant nothing to CN={enclave}']
    if not grant.valid_at(when):
        problems.append(f'{what} are not valid now')
    covered = sorted({d for rule in grant.rules if rule.allow for d in rule.domains})
    if domain is not None and domain not in covered:
        problems.append(f'{what} cover {_domains_phrase(covered)}, not {domain}')
    return problems


def _warn(reason: str) -> None:
    """Permissive: carry on with the material as it is, and say what is wrong once."""
    _warn_once(reason, f'SECURITY: {reason} (going on: {STRATEGY_ENV} is not Enforce)')


def _warn_once(reason: str, text: str) -> None:
    """Log `text` the first time `reason` comes up in this process (permissive modes)."""
    if reason in _reported:
        return
    _reported.add(reason)
    from ros2lite.logging import get_logger

    get_logger('ros2lite.security').warn(text)


def _decide(
    keystore_raw: str, enclave: str, env: Mapping[str, str] | None, domain: int | None
) -> Identity | None:
    if not keystore_raw:
        reason = f'{ENABLE_ENV}=true but {KEYSTORE_ENV} is not set'
    else:
        found = _identity(Path(keystore_raw), enclave)
        if isinstance(found, Identity):
            problems = enclave_problems(found, domain)
            if problems and enforced(env):
                raise SecurityError(f'SECURITY ERROR: {problems[0]} ({STRATEGY_ENV}=Enforce)')
            for problem in problems:
                _warn(problem)
            return found
        reason = found
    if enforced(env):
        raise SecurityError(f'SECURITY ERROR: {reason} ({STRATEGY_ENV}=Enforce)')
    _fallback(reason)
    return None


def resolve(
    env: Mapping[str, str] | None = None,
    enclave: str | None = None,
    domain_id: int | None = None,
) -> Identity | None:
    """This process's identity when security applies; None when it is off, or Permissive
    without material.  Enforce without material, or with material the router would refuse
    (:func:`enclave_problems`; ``domain_id`` defaults to ``ROS_DOMAIN_ID``), raises
    :class:`SecurityError`."""
    environ = _env(env)
    if not security_enabled(environ):
        return None
    name = environ.get(OVERRIDE_ENV, '') or enclave or process_enclave()
    try:
        validate_enclave_name(name)
    except EnclaveError as exc:
        if enforced(environ):
            raise SecurityError(f'SECURITY ERROR: {exc}') from None
        _fallback(str(exc))
        return None
    domain = env_domain_id(environ) if domain_id is None else domain_id
    return _decide(environ.get(KEYSTORE_ENV, ''), name, environ, domain)


def router_identity(env: Mapping[str, str] | None = None) -> Identity | None:
    """The daemon's identity: its own enclave, created on first use if the CA key is here."""
    environ = _env(env)
    if not security_enabled(environ):
        return None
    keystore_raw = environ.get(KEYSTORE_ENV, '')
    name = environ.get(ROUTER_ENCLAVE_ENV, '') or DEFAULT_ROUTER_ENCLAVE
    validate_enclave_name(name)
    if keystore_raw:
        keystore = Path(keystore_raw)
        if not isinstance(_identity(keystore, name), Identity):
            from ros2lite.security.keystore import create_enclave, is_valid_keystore

            if is_valid_keystore(keystore):  # its CA keys are here: make the router one
                create_enclave(keystore, name)
    return _decide(keystore_raw, name, environ, None)  # a router serves every domain
