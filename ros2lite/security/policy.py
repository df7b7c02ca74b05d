"""sros2's policy documents: load (with XInclude), check, write back, and grow from a graph.

A policy is ``policy[@version]/enclaves/enclave[@path]/profiles/profile[@ns][@node]``
holding ``topics`` (``publish``/``subscribe``), ``services`` (``reply``/``request``) and
``actions`` (``call``/``execute``) lists, each attribute ``ALLOW`` or ``DENY``.  Elements are
kept as ElementTree nodes so a loaded policy is written back with everything it had.

Written policies are ordered as sros2's ``policy.xsl`` orders them (attributes by name;
children by tag, then text, then ``ns``+``node``, then ``path``; repeated names dropped), so
``generate_policy`` output compares equal across tools.
"""

from __future__ import annotations

import copy
import enum
import re
import xml.etree.ElementTree as ET
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Protocol

from ros2lite.security.enclaves import validate_enclave_name
from ros2lite.security.errors import EnclaveError, PolicyError
from ros2lite.security.files import parse_xml, read_bytes

__all__ = [
    'POLICY_VERSION',
    'GraphEntity',
    'NodeAccess',
    'add_node_access',
    'default_policy',
    'dump_policy',
    'enclave_paths',
    'graph_access',
    'load_policy',
    'new_policy',
    'policy_for_enclave',
]

POLICY_VERSION = '0.2.0'
XINCLUDE = '{http://www.w3.org/2001/XInclude}include'
MAX_INCLUDE_DEPTH = 8

# list element → (item element, the attributes it may carry)
LISTS = {
    'topics': ('topic', ('publish', 'subscribe')),
    'services': ('service', ('reply', 'request')),
    'actions': ('action', ('call', 'execute')),
}
QUALIFIERS = ('ALLOW', 'DENY')
# what a name in a policy may hold: a ROS name, relative or private, with '*' wildcards
_EXPRESSION = re.compile(r'(~/?|/)?[A-Za-z0-9_*{}]+(/[A-Za-z0-9_*{}]+)*')


def new_policy() -> ET.Element:
    """An empty policy: ``<policy version="0.2.0"><enclaves/></policy>``."""
    root = ET.Element('policy', version=POLICY_VERSION)
    ET.SubElement(root, 'enclaves')
    return root


def default_policy(enclave: str) -> ET.Element:
    """sros2's default for a new enclave: every topic, service and action allowed."""
    root = new_policy()
    node = ET.SubElement(root.find('enclaves'), 'enclave', path=enclave)  # type: ignore[arg-type]
    profile = ET.SubElement(ET.SubElement(node, 'profiles'), 'profile', ns='/', node='default')
    for list_tag, (item, attrs) in LISTS.items():
        group = ET.SubElement(profile, list_tag, {a: 'ALLOW' for a in attrs})
        ET.SubElement(group, item).text = '/*'
    return root


# -- loading ---------------------------------------------------------------------------------


def _xpointer_children(doc: ET.Element, xpointer: str, origin: str) -> list[ET.Element]:
    """What ``xpointer(/a/b/*)`` or ``xpointer(/a/b)`` selects (the forms sros2 uses)."""
    m = re.fullmatch(r'xpointer\((/[A-Za-z_][\w.-]*(?:/[A-Za-z_][\w.-]*)*)(/\*)?\)', xpointer)
    if not m:
        raise PolicyError(f'{origin}: unsupported xpointer {xpointer!r}')
    steps = m.group(1).strip('/').split('/')
    if doc.tag != steps[0]:
        return []
    nodes = [doc]
    for step in steps[1:]:
        nodes = [child for node in nodes for child in node if child.tag == step]
    if m.group(2):
        return [child for node in nodes for child in node]
    return nodes


def _include(element: ET.Element, base: Path, depth: int, origin: str) -> None:
    """Replace ``xi:include`` elements below ``element`` by what they point at (files only)."""
    for index, child in reversed(list(enumerate(element))):
        if child.tag != XINCLUDE:
            _include(child, base, depth, origin)
            continue
        href = child.get('href', '')
        if not href or re.match(r'^[A-Za-z][A-Za-z0-9+.-]*:', href):
            raise PolicyError(f'{origin}: xi:include needs a relative file href, got {href!r}')
        if depth >= MAX_INCLUDE_DEPTH:
            raise PolicyError(f'{origin}: xi:include nested deeper than {MAX_INCLUDE_DEPTH}')
        path = (base / href).resolve()
        sub = parse_xml(read_bytes(path, 'included file'), str(path))
        _include(sub, path.parent, depth + 1, str(path))
        xpointer = child.get('xpointer')
        parts = _xpointer_children(sub, xpointer, origin) if xpointer else [sub]
        element.remove(child)
        for offset, part in enumerate(parts):
            element.insert(index + offset, copy.deepcopy(part))


def _check(root: ET.Element, origin: str) -> None:
    """Structure and values sros2's schema asks for; names must be ROS names (with '*')."""

    def fail(why: str) -> PolicyError:
        return PolicyError(f'{origin}: {why}')

    if root.tag != 'policy':
        raise fail(f"the root element is <{root.tag}>, not <policy>")
    if not root.get('version'):
        raise fail('<policy> has no version attribute')
    enclaves = root.findall('enclaves')
    if len(enclaves) != 1:
        raise fail('<policy> must hold exactly one <enclaves>')
    for enclave in enclaves[0]:
        if enclave.tag != 'enclave' or not enclave.get('path'):
            raise fail('<enclaves> may hold only <enclave path="..."> elements')
        try:
            validate_enclave_name(enclave.get('path', ''))
        except EnclaveError as exc:
            raise fail(str(exc)) from None
        for profiles in enclave:
            if profiles.tag != 'profiles':
                raise fail(f'unexpected <{profiles.tag}> in <enclave>')
            for profile in profiles:
                if profile.tag == 'metadata':
                    continue
                if profile.tag != 'profile' or profile.get('ns') is None or not profile.get('node'):
                    raise fail('<profiles> may hold only <profile ns="..." node="...">')
                _check_profile(profile, fail)


def _check_profile(profile: ET.Element, fail: Callable[[str], PolicyError]) -> None:
    for group in profile:
        if group.tag not in LISTS:
            raise fail(f'unexpected <{group.tag}> in <profile>')
        item, attrs = LISTS[group.tag]
        for name, value in group.attrib.items():
            if name in attrs and value not in QUALIFIERS:
                raise fail(f'{group.tag}/@{name} must be ALLOW or DENY, not {value!r}')
        if not any(a in group.attrib for a in attrs):
            raise fail(f'<{group.tag}> has none of {", ".join(attrs)}')
        for entry in group:
            text = (entry.text or '').strip()
            if entry.tag != item or not _EXPRESSION.fullmatch(text):
                raise fail(f'bad <{entry.tag}> {text!r} in <{group.tag}>')
            entry.text = text


def load_policy(path: Path) -> ET.Element:
    """Read, expand and check a policy file; every problem is one PolicyError line."""
    if not path.is_file():
        raise PolicyError(f"policy file '{path}' does not exist")
    origin = str(path)
    root = parse_xml(read_bytes(path, 'policy file'), origin)
    _include(root, path.resolve().parent, 0, origin)
    _strip(root)
    _check(root, origin)
    return root


def _strip(element: ET.Element) -> None:
    """Drop whitespace-only text, as xsl:strip-space does."""
    if element.text is not None and not element.text.strip():
        element.text = None
    element.tail = None
    for child in element:
        _strip(child)


def enclave_paths(policy: ET.Element) -> list[str]:
    """The enclaves a policy describes, in document order."""
    return [e.get('path', '') for e in policy.findall('enclaves/enclave')]


def policy_for_enclave(policy: ET.Element, enclave: str) -> ET.Element:
    """A policy holding only ``enclave`` (what one permissions file is made from)."""
    for element in policy.findall('enclaves/enclave'):
        if element.get('path') == enclave:
            root = ET.Element('policy', version=policy.get('version', POLICY_VERSION))
            ET.SubElement(root, 'enclaves').append(copy.deepcopy(element))
            return root
    raise PolicyError(f'unable to find enclave "{enclave}" in the policy')


# -- writing ---------------------------------------------------------------------------------


def _sort_key(element: ET.Element) -> tuple[str, str, str, str]:
    return (
        element.tag,
        element.text or '',
        element.get('ns', '') + element.get('node', ''),
        element.get('path', ''),
    )


def _ordered(element: ET.Element) -> ET.Element:
    out = ET.Element(element.tag, dict(sorted(element.attrib.items())))
    out.text = element.text
    seen: set[tuple[str, str]] = set()
    for child in sorted(element, key=_sort_key):
        if child.tag in ('topic', 'service', 'action'):
            mark = (child.tag, child.text or '')
            if mark in seen:
                continue
            seen.add(mark)
        out.append(_ordered(child))
    return out


def dump_policy(policy: ET.Element) -> str:
    """The policy as sros2 writes it: ordered, deduplicated, two-space indented."""
    ordered = _ordered(policy)
    ET.indent(ordered, space='  ')
    return ET.tostring(ordered, encoding='unicode') + '\n'


# -- growing from a graph ----------------------------------------------------------------------


@dataclass
class NodeAccess:
    """What one live node does, as ``generate_policy`` records it."""

    name: str
    namespace: str
    enclave: str
    publishes: list[str] = field(default_factory=list)
    subscribes: list[str] = field(default_factory=list)
    serves: list[str] = field(default_factory=list)
    calls: list[str] = field(default_factory=list)

    @property
    def fqn(self) -> str:
        """'/namespace/name' of the node."""
        return self.namespace.rstrip('/') + '/' + self.name


def _relative(name: str, node: NodeAccess) -> str:
    """sros2's shortening: ``~/x`` below the node, relative below its namespace."""
    if name.startswith(node.fqn + '/'):
        return '~' + name[len(node.fqn) :]
    if name.startswith(node.namespace + '/') and node.namespace != '/':
        return name[len(node.namespace) + 1 :]
    if node.namespace == '/' and name.count('/') == 1:
        return name[1:]
    return name


def _find_or_add(parent: ET.Element, tag: str, match: dict[str, str]) -> ET.Element:
    for child in parent.findall(tag):
        if all(child.get(k) == v for k, v in match.items()):
            return child
    return ET.SubElement(parent, tag, match)


def add_node_access(policy: ET.Element, nodes: Iterable[NodeAccess]) -> None:
    """Add what each node does to its enclave's profile (ALLOW), creating what is missing."""
    enclaves = policy.find('enclaves')
    if enclaves is None:
        raise PolicyError("policy is missing an 'enclaves' element")
    for node in nodes:
        enclave = _find_or_add(enclaves, 'enclave', {'path': node.enclave})
        profiles = enclave.find('profiles')
        if profiles is None:
            profiles = ET.SubElement(enclave, 'profiles')
        profile = _find_or_add(profiles, 'profile', {'ns': node.namespace, 'node': node.name})
        for tag, item, attr, names in (
            ('topics', 'topic', 'subscribe', node.subscribes),
            ('topics', 'topic', 'publish', node.publishes),
            ('services', 'service', 'reply', node.serves),
            ('services', 'service', 'request', node.calls),
        ):
            if not names:
                continue
            group = _find_or_add(profile, tag, {attr: 'ALLOW'})
            for name in names:
                ET.SubElement(group, item).text = _relative(name, node)


class GraphEntity(Protocol):
    """A node or endpoint of a graph snapshot, as :func:`graph_access` reads it (the graph's
    own entities are such; this package does not import the transport that parses them)."""

    @property
    def zid(self) -> str: ...
    @property
    def nid(self) -> int: ...
    @property
    def kind(self) -> enum.Enum: ...
    @property
    def is_node(self) -> bool: ...
    @property
    def enclave(self) -> str: ...
    @property
    def namespace(self) -> str: ...
    @property
    def node_name(self) -> str: ...
    @property
    def topic_name(self) -> str | None: ...


def graph_access(entities: Iterable[GraphEntity]) -> list[NodeAccess]:
    """What every visible node of a graph snapshot does, one entry per node instance with
    its own enclave (hidden nodes are left out, as sros2's ``generate_policy`` does)."""
    listed = list(entities)
    nodes = {
        (e.zid, e.nid): e
        for e in listed
        if e.is_node and e.node_name and not e.node_name.startswith('_')
    }
    names: dict[tuple[str, int, str], set[str]] = {}
    for e in listed:
        if not e.is_node and e.topic_name and (e.zid, e.nid) in nodes:
            names.setdefault((e.zid, e.nid, e.kind.name), set()).add(e.topic_name)

    def of(node: GraphEntity, kind: str) -> list[str]:
        return sorted(names.get((node.zid, node.nid, kind), ()))

    return [
        NodeAccess(
            node.node_name,
            node.namespace,
            node.enclave,
            publishes=of(node, 'PUBLISHER'),
            subscribes=of(node, 'SUBSCRIPTION'),
            serves=of(node, 'SERVICE'),
            calls=of(node, 'CLIENT'),
        )
        for node in sorted(nodes.values(), key=lambda n: (n.namespace, n.node_name, n.enclave))
    ]
