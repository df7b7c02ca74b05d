"""From an sros2 keystore's permissions to the Zenoh router's access-control rules.

The router sees every message of a secured graph (secured sessions are clients, so nothing
goes peer to peer around it).  Each enclave becomes a subject matched by its certificate's
common name; each grant of its own ``permissions.xml`` becomes rules on rmw_zenoh key
expressions, seen from the router (``ingress``: from that enclave, ``egress``: to it):

============================  ==========================================================
permission (DDS name)         router rules on ``<domain>/<name>/<type>/<hash>`` (= K)
============================  ==========================================================
publish topic (``rt/N``)      in: put, delete, reply on K; declare_queryable, liveliness_token
                              on K/@adv/pub/** (the TRANSIENT_LOCAL cache); out:
                              declare_subscriber on K, query on K/@adv/**, subscriber tokens
subscribe topic (``rt/N``)    in: declare_subscriber on K, its token on K/@adv/sub/**, query
                              and liveliness interest on K/@adv/**; out: put, delete, reply
                              on K; declare_queryable, liveliness_token, reply on K/@adv/pub/**
serve (``rq/NRequest`` sub,   out: query on K; in: declare_queryable, reply on K
``rr/NReply`` pub)
call (``rq/NRequest`` pub,    in: query on K; out: declare_queryable, reply on K
``rr/NReply`` sub)
============================  ==========================================================

Graph tokens are bound as DDS binds discovery: an enclave may declare liveliness tokens
only with its own name in their enclave chunk, a node token (``NN``) in its domains, and an
endpoint token only for what it may do: ``MP``/``MS`` on topics it may publish/subscribe,
``SS``/``SC`` on services it may serve/call.  Every enclave with a valid grant also reads
every token (``@ros2_lv/**``) and the router's admin space (``@/**``).
Everything else is denied (``default_permission: deny``); an enclave with no grant, with
permissions the permissions CA did not sign as they are (``permissions.p7s``), or a
certificate the keystore does not know, gets nothing.  DENY rules win over ALLOW rules, as
in DDS.  In a name ``*`` as a whole segment stands for one or more segments; inside a segment
it matches within that segment (ALLOW) or, to stay on the safe side, the whole segment and
what follows (DENY).
"""

from __future__ import annotations

import datetime
import re
from collections.abc import Iterable
from dataclasses import dataclass, field
from pathlib import Path

from ros2lite.security.errors import SecurityError
from ros2lite.security.permissions import Grant, parse_permissions

__all__ = [
    'AccessControl',
    'AccessRule',
    'AccessSubject',
    'keys_for_name',
    'router_access',
    'token_topic',
]

INGRESS, EGRESS = 'ingress', 'egress'
_SEGMENT = re.compile(r'[A-Za-z0-9_]+')
_PARTIAL = re.compile(r'[A-Za-z0-9_*]+')


@dataclass(frozen=True)
class AccessRule:
    """One Zenoh ACL rule (key expressions may still need canonising)."""

    id: str
    allow: bool
    flow: str
    messages: tuple[str, ...]
    key_exprs: tuple[str, ...]


@dataclass(frozen=True)
class AccessSubject:
    """One enclave as the router knows it: by its certificate's common name."""

    id: str
    common_name: str
    rules: tuple[str, ...]


@dataclass
class AccessControl:
    """What the router enforces, plus what it had to leave out (said in its log)."""

    rules: list[AccessRule] = field(default_factory=list)
    subjects: list[AccessSubject] = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)


class _Invalid(ValueError):
    pass


def keys_for_name(name: str, domain_id: int, *, allow: bool) -> str:
    """The key expression of the data of topic/service ``name`` (a ROS name, ``*`` allowed)."""
    tokens: list[str] = []
    for segment in name.strip('/').split('/'):
        if _SEGMENT.fullmatch(segment):
            tokens.append(segment)
        elif segment == '*':
            tokens += ['*', '**']
        elif _PARTIAL.fullmatch(segment):
            tokens += [segment.replace('*', '$*')] if allow else ['*', '**']
        else:
            raise _Invalid(name)
    return f'{domain_id}/' + '/'.join(tokens) + '/*/*'


def token_topic(name: str, *, allow: bool) -> str:
    """The topic chunk of a graph token for ``name`` (``/a/b`` → ``%a%b``, ``*`` allowed):
    one chunk, so ``*`` becomes ``$*``, which also spans the ``%`` of deeper names."""
    chunk = ''
    for segment in name.strip('/').split('/'):
        if _SEGMENT.fullmatch(segment):
            chunk += '%' + segment
        elif segment == '*' or (_PARTIAL.fullmatch(segment) and not allow):
            return chunk + '%$*'
        elif _PARTIAL.fullmatch(segment):
            chunk += '%' + segment.replace('*', '$*')
        else:
            raise _Invalid(name)
    return chunk


def _token(domain: int, kind: str, enclave: str, topic: str | None = None) -> str:
    """The tokens of ``kind`` an enclave may declare (rmw_zenoh's key layout)."""
    head = f'@ros2_lv/{domain}/*/*/*/{kind}/{enclave.replace("/", "%")}/*/*'
    return head if topic is None else f'{head}/{topic}/**'


_TOKEN_KINDS = {'publish': 'MP', 'subscribe': 'MS', 'serve': 'SS', 'call': 'SC'}


def _service_name(dds: str, prefix: str, suffix: str) -> str | None:
    if not dds.startswith(prefix):
        return None
    name = dds[len(prefix) :]
    if name.endswith(suffix):
        name = name[: -len(suffix)]
    elif not name.endswith('*'):
        raise _Invalid(dds)
    return '/' + name if name else None


# (direction of the DDS permission, DDS prefix, suffix) → role
_ROLES = (
    ('publish', 'rt/', '', 'publish'),
    ('subscribe', 'rt/', '', 'subscribe'),
    ('subscribe', 'rq/', 'Request', 'serve'),
    ('publish', 'rr/', 'Reply', 'serve'),
    ('publish', 'rq/', 'Request', 'call'),
    ('subscribe', 'rr/', 'Reply', 'call'),
)


def _role_rules(role: str, key: str) -> list[tuple[str, tuple[str, ...], str]]:
    """(flow, messages, key) triples a role needs on one data key expression."""
    adv, adv_pub, adv_sub = f'{key}/@adv/**', f'{key}/@adv/pub/**', f'{key}/@adv/sub/**'
    if role == 'publish':
        return [
            (INGRESS, ('put', 'delete', 'reply'), key),
            (INGRESS, ('declare_queryable', 'liveliness_token'), adv_pub),
            (INGRESS, ('declare_liveliness_subscriber', 'liveliness_query'), adv),
            (EGRESS, ('declare_subscriber',), key),
            (EGRESS, ('query',), adv),
            (EGRESS, ('liveliness_token', 'reply'), adv_sub),
        ]
    if role == 'subscribe':
        return [
            (INGRESS, ('declare_subscriber',), key),
            (INGRESS, ('liveliness_token',), adv_sub),
            (INGRESS, ('query', 'declare_liveliness_subscriber', 'liveliness_query'), adv),
            (EGRESS, ('put', 'delete', 'reply'), key),
            (EGRESS, ('declare_queryable', 'liveliness_token', 'reply'), adv_pub),
        ]
    if role == 'serve':
        return [(EGRESS, ('query',), key), (INGRESS, ('declare_queryable', 'reply'), key)]
    return [(INGRESS, ('query',), key), (EGRESS, ('declare_queryable', 'reply'), key)]


def _graph_rules(domains: Iterable[int], enclave: str) -> list[tuple[str, tuple[str, ...], str]]:
    rules = [(INGRESS, ('liveliness_token',), _token(d, 'NN', enclave)) for d in sorted(domains)]
    return [
        *rules,
        (INGRESS, ('declare_liveliness_subscriber', 'liveliness_query'), '@ros2_lv/**'),
        (EGRESS, ('liveliness_token', 'reply'), '@ros2_lv/**'),
        (INGRESS, ('query',), '@/**'),
        (EGRESS, ('reply',), '@/**'),
    ]


def _grant_rules(
    grant: Grant, enclave: str
) -> tuple[dict[tuple[bool, str, tuple[str, ...]], set[str]], set[int], list[str]]:
    """Rules of one grant, grouped; the domains it covers; the names it had to skip."""
    grouped: dict[tuple[bool, str, tuple[str, ...]], set[str]] = {}
    domains: set[int] = set()
    skipped: list[str] = []
    for rule in grant.rules:
        domains.update(rule.domains)
        for direction, names in (('publish', rule.publish), ('subscribe', rule.subscribe)):
            for dds in names:
                for wanted, prefix, suffix, role in _ROLES:
                    if wanted != direction or not dds.startswith(prefix):
                        continue
                    try:
                        name = (
                            '/' + dds[len(prefix) :]
                            if not suffix
                            else _service_name(dds, prefix, suffix)
                        )
                        if not name or name == '/':
                            raise _Invalid(dds)
                        topic = token_topic(name, allow=rule.allow)
                        for domain in rule.domains:
                            key = keys_for_name(name, domain, allow=rule.allow)
                            token = _token(domain, _TOKEN_KINDS[role], enclave, topic)
                            for flow, messages, ke in [
                                *_role_rules(role, key),
                                (INGRESS, ('liveliness_token',), token),
                            ]:
                                grouped.setdefault((rule.allow, flow, messages), set()).add(ke)
                    except _Invalid:
                        if not rule.allow:
                            raise
                        skipped.append(dds)
    return grouped, domains, skipped


def _enclaves(keystore: Path) -> Iterable[tuple[str, Path]]:
    base = keystore / 'enclaves'
    for permissions in sorted(base.glob('**/permissions.xml')):
        relative = permissions.parent.relative_to(base).as_posix()
        yield ('/' + relative).replace('/.', '/'), permissions


def router_access(keystore: Path, now: datetime.datetime | None = None) -> AccessControl:
    """The access control for a router serving ``keystore``'s enclaves (module doc)."""
    when = now or datetime.datetime.now(datetime.timezone.utc)
    if not (keystore / 'enclaves').is_dir():
        raise SecurityError(f"'{keystore}' is not a keystore (no enclaves directory)")
    from ros2lite.security.pki import read_signed

    result = AccessControl()
    permissions_ca = keystore / 'public' / 'permissions_ca.cert.pem'
    for index, (enclave, path) in enumerate(_enclaves(keystore)):
        try:
            signature = path.with_name('permissions.p7s')
            what = f'permissions of enclave {enclave}'
            document = read_signed(path, signature, permissions_ca, what)
            grants = parse_permissions(document, str(path))
        except SecurityError as exc:
            result.warnings.append(f'{enclave}: ignored ({exc})')
            continue
        grant = next((g for g in grants if g.common_name == enclave), None)
        if grant is None:
            result.warnings.append(f'{enclave}: its permissions grant nothing to CN={enclave}')
            continue
        if not grant.valid_at(when):
            result.warnings.append(f'{enclave}: its grant is not valid now; enclave denied')
            continue
        try:
            grouped, domains, skipped = _grant_rules(grant, enclave)
        except _Invalid as exc:
            result.warnings.append(f'{enclave}: unsupported DENY name {exc}; enclave denied')
            continue
        for name in skipped:
            result.warnings.append(f'{enclave}: unsupported ALLOW name {name} left out')
        subject = f'enclave{index}'
        ids = []
        entries = sorted(grouped.items()) + [
            ((True, flow, messages), {key})
            for flow, messages, key in _graph_rules(domains, enclave)
        ]
        for n, ((allow, flow, messages), keys) in enumerate(entries):
            rule_id = f'{subject}-{n}'
            ids.append(rule_id)
            result.rules.append(AccessRule(rule_id, allow, flow, messages, tuple(sorted(keys))))
        result.subjects.append(AccessSubject(subject, enclave, tuple(ids)))
    return result
