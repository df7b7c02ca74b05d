"""DDS-Security documents of an sros2 keystore: governance, and permissions made from a policy.

Permissions are made as sros2's ``permissions.xsl`` makes them, so the files (and their
signatures) are what a DDS-based ROS 2 expects: one ``grant`` per enclave with
``subject_name CN=<enclave>``, the certificate's validity, a ``deny_rule`` then an
``allow_rule`` listing DDS topic names (``rt/<topic>``, ``rq/<service>Request``,
``rr/<service>Reply``; actions expand to their services and topics) and ``default DENY``.

The same files are read back (:func:`parse_permissions`) to make the Zenoh router's access
rules (see :mod:`ros2lite.security.access`).
"""

from __future__ import annotations

import datetime
import re
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field

from ros2lite.security.errors import PolicyError
from ros2lite.security.files import parse_xml
from ros2lite.util.domain import DDS_MAX_DOMAIN_ID

__all__ = [
    'Grant',
    'Rule',
    'governance_xml',
    'parse_permissions',
    'permissions_xml',
]

XSI = 'http://www.w3.org/2001/XMLSchema-instance'
PERMISSIONS_SCHEMA = 'http://www.omg.org/spec/DDS-SECURITY/20170901/omg_shared_ca_permissions.xsd'
GOVERNANCE_SCHEMA = 'http://www.omg.org/spec/DDS-SECURITY/20170901/omg_shared_ca_governance.xsd'
ET.register_namespace('xsi', XSI)

_ACTION_SERVICES = ('cancel_goal', 'get_result', 'send_goal')
_ACTION_TOPICS = ('feedback', 'status')


def _dds_root(schema: str) -> ET.Element:
    return ET.Element('dds', {f'{{{XSI}}}noNamespaceSchemaLocation': schema})


def _text(parent: ET.Element, tag: str, text: str) -> ET.Element:
    element = ET.SubElement(parent, tag)
    element.text = text
    return element


def _serialize(root: ET.Element) -> bytes:
    ET.indent(root, space='  ')
    return ET.tostring(root, encoding='unicode').encode() + b'\n'


def governance_xml(domain_id: int) -> bytes:
    """sros2's governance: authenticated participants only, everything encrypted."""
    root = _dds_root(GOVERNANCE_SCHEMA)
    rule = ET.SubElement(ET.SubElement(root, 'domain_access_rules'), 'domain_rule')
    _text(ET.SubElement(rule, 'domains'), 'id', str(domain_id))
    for tag, value in (
        ('allow_unauthenticated_participants', 'false'),
        ('enable_join_access_control', 'true'),
        ('discovery_protection_kind', 'ENCRYPT'),
        ('liveliness_protection_kind', 'ENCRYPT'),
        ('rtps_protection_kind', 'ENCRYPT'),
    ):
        _text(rule, tag, value)
    topic_rule = ET.SubElement(ET.SubElement(rule, 'topic_access_rules'), 'topic_rule')
    for tag, value in (
        ('topic_expression', '*'),
        ('enable_discovery_protection', 'true'),
        ('enable_liveliness_protection', 'true'),
        ('enable_read_access_control', 'true'),
        ('enable_write_access_control', 'true'),
        ('metadata_protection_kind', 'ENCRYPT'),
        ('data_protection_kind', 'ENCRYPT'),
    ):
        _text(topic_rule, tag, value)
    return b'<?xml version="1.0" encoding="UTF-8"?>\n' + _serialize(root)


# -- policy → permissions --------------------------------------------------------------------


def _delimited(namespace: str) -> str:
    return namespace if namespace.endswith('/') else namespace + '/'


def _full_name(name: str, namespace: str, node: str) -> str:
    """A policy name made absolute the way the XSL does it."""
    if name.startswith('/'):
        return name
    if name.startswith('~'):
        return _delimited(namespace) + node + name[1:]
    return _delimited(namespace) + name


def _translate(
    group: ET.Element, qualifier: str, namespace: str, node: str
) -> list[tuple[str, list[str]]]:
    """(``publish`` or ``subscribe``, DDS topic names) blocks for one list element."""
    names = [_full_name(e.text or '', namespace, node) for e in group]
    blocks: list[tuple[str, list[str]]] = []

    def add(kind: str, topics: list[str]) -> None:
        blocks.append((kind, topics))

    if group.get('publish') == qualifier:
        add('publish', [f'rt{n}' for n in names])
    if group.get('subscribe') == qualifier:
        add('subscribe', [f'rt{n}' for n in names])
    if group.get('request') == qualifier:
        add('publish', [f'rq{n}Request' for n in names])
        add('subscribe', [f'rr{n}Reply' for n in names])
    if group.get('reply') == qualifier:
        add('publish', [f'rr{n}Reply' for n in names])
        add('subscribe', [f'rq{n}Request' for n in names])
    requests = [f'rq{n}/_action/{s}Request' for n in names for s in _ACTION_SERVICES]
    replies_and_topics = [
        t
        for n in names
        for t in (
            *(f'rr{n}/_action/{s}Reply' for s in _ACTION_SERVICES),
            *(f'rt{n}/_action/{t}' for t in _ACTION_TOPICS),
        )
    ]
    if group.get('call') == qualifier:
        add('publish', requests)
        add('subscribe', replies_and_topics)
    if group.get('execute') == qualifier:
        add('publish', replies_and_topics)
        add('subscribe', requests)
    return blocks


def _rule(tag: str, domain_id: int, blocks: list[list[str]], kinds: list[str]) -> ET.Element:
    """One allow/deny rule: each kind's blocks sorted by their first name, merged, deduped."""
    rule = ET.Element(tag)
    _text(ET.SubElement(rule, 'domains'), 'id', str(domain_id))
    for kind in ('publish', 'subscribe'):
        groups = [names for k, names in zip(kinds, blocks, strict=True) if k == kind]
        if not groups:
            continue
        topics = ET.SubElement(ET.SubElement(rule, kind), 'topics')
        seen: set[str] = set()
        for names in sorted(groups, key=lambda g: g[0] if g else ''):
            for name in names:
                if name not in seen:
                    seen.add(name)
                    _text(topics, 'topic', name)
    return rule


def permissions_xml(
    policy: ET.Element,
    domain_id: int,
    not_before: datetime.datetime,
    not_after: datetime.datetime,
) -> bytes:
    """The DDS permissions document for every enclave of ``policy``."""
    root = _dds_root(PERMISSIONS_SCHEMA)
    permissions = ET.SubElement(root, 'permissions')
    for enclave in policy.findall('enclaves/enclave'):
        name = enclave.get('path', '')
        for profiles in enclave.findall('profiles'):
            grant = ET.SubElement(permissions, 'grant', name=name)
            _text(grant, 'subject_name', f'CN={name}')
            validity = ET.SubElement(grant, 'validity')
            _text(validity, 'not_before', not_before.isoformat())
            _text(validity, 'not_after', not_after.isoformat())
            for qualifier, tag in (('DENY', 'deny_rule'), ('ALLOW', 'allow_rule')):
                kinds: list[str] = []
                blocks: list[list[str]] = []
                for profile in profiles.findall('profile'):
                    ns, node = profile.get('ns', '/'), profile.get('node', '')
                    for group in profile:
                        if qualifier not in group.attrib.values():
                            continue
                        for kind, names in _translate(group, qualifier, ns, node):
                            kinds.append(kind)
                            blocks.append(names)
                if kinds:
                    grant.append(_rule(tag, domain_id, blocks, kinds))
            _text(grant, 'default', 'DENY')
    return _serialize(root)


# -- permissions → grants ----------------------------------------------------------------------


@dataclass(frozen=True)
class Rule:
    """One allow or deny rule of a grant: DDS topic expressions per direction."""

    allow: bool
    domains: tuple[int, ...]
    publish: tuple[str, ...] = ()
    subscribe: tuple[str, ...] = ()


@dataclass(frozen=True)
class Grant:
    """What a permissions document grants one subject."""

    name: str
    common_name: str
    not_before: datetime.datetime | None
    not_after: datetime.datetime | None
    rules: tuple[Rule, ...] = field(default_factory=tuple)

    def valid_at(self, when: datetime.datetime) -> bool:
        """Whether the grant's validity period includes `when`."""
        return (self.not_before is None or self.not_before <= when) and (
            self.not_after is None or when <= self.not_after
        )


MAX_DOMAIN_ID = DDS_MAX_DOMAIN_ID


def _time(text: str | None, origin: str) -> datetime.datetime | None:
    if not text:
        return None
    try:
        value = datetime.datetime.fromisoformat(text.strip().replace('Z', '+00:00'))
    except ValueError:
        raise PolicyError(f'{origin}: bad validity time {text!r}') from None
    return value if value.tzinfo else value.replace(tzinfo=datetime.timezone.utc)


def _domains(element: ET.Element | None, origin: str) -> tuple[int, ...]:
    if element is None:
        return ()
    ids: set[int] = set()
    try:
        for child in element:
            if child.tag == 'id':
                ids.add(int((child.text or '').strip()))
            elif child.tag == 'id_range':
                low = int((child.findtext('min') or '0').strip())
                high = int((child.findtext('max') or str(MAX_DOMAIN_ID)).strip())
                ids.update(range(max(low, 0), min(high, MAX_DOMAIN_ID) + 1))
    except ValueError:
        raise PolicyError(f'{origin}: bad domain id') from None
    return tuple(sorted(i for i in ids if 0 <= i <= MAX_DOMAIN_ID))


def _common_name(subject: str) -> str:
    """The CN of a DN written ``CN=/a/b`` or ``C=x, CN=/a/b, O=y``."""
    for part in re.split(r'\s*[,;]\s*', subject.strip()):
        key, _, value = part.partition('=')
        if key.strip().upper() == 'CN':
            return value.strip()
    return ''


def parse_permissions(data: bytes, origin: str) -> list[Grant]:
    """The grants of a DDS permissions document (``dds/permissions/grant``)."""
    root = parse_xml(data, origin)
    if root.tag != 'dds' or root.find('permissions') is None:
        raise PolicyError(f'{origin}: not a DDS permissions document')
    grants = []
    for grant in root.findall('permissions/grant'):
        rules = []
        for element in grant:
            if element.tag not in ('allow_rule', 'deny_rule'):
                continue
            rules.append(
                Rule(
                    allow=element.tag == 'allow_rule',
                    domains=_domains(element.find('domains'), origin),
                    publish=tuple(
                        (t.text or '').strip() for t in element.findall('publish/topics/topic')
                    ),
                    subscribe=tuple(
                        (t.text or '').strip() for t in element.findall('subscribe/topics/topic')
                    ),
                )
            )
        grants.append(
            Grant(
                name=grant.get('name', ''),
                common_name=_common_name(grant.findtext('subject_name') or ''),
                not_before=_time(grant.findtext('validity/not_before'), origin),
                not_after=_time(grant.findtext('validity/not_after'), origin),
                rules=tuple(rules),
            )
        )
    return grants
