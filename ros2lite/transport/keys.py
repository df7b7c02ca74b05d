"""The Zenoh keys rmw_zenoh builds from ROS names and types.

Two things live here because they must agree byte for byte with rmw_zenoh_cpp: the data key
expression ``<domain>/<name>/<dds type>/<hash>``, and the ``@ros2_lv`` liveliness tokens that
make up the ROS graph (the rules for the names themselves are :mod:`ros2lite.names`'). Token
parsing is lenient: peers from other releases add chunks or use old QoS defaults, and a graph
view must not fall over on one odd token.
"""

from __future__ import annotations

import enum
import functools
from dataclasses import dataclass

from ros2lite.names import node_fqn
from ros2lite.qos import QoSProfile
from ros2lite.transport.qos import decode_qos, encode_qos

__all__ = [
    "LIVELINESS_PREFIX",
    "Entity",
    "EntityKind",
    "dds_type_name",
    "demangle",
    "endpoint_token",
    "liveliness_prefix",
    "liveliness_subscription_key",
    "mangle",
    "node_token",
    "parse_token",
    "ros_type_name",
    "topic_key",
]

LIVELINESS_PREFIX = "@ros2_lv"

# --------------------------------------------------------------------------- types and keys


def dds_type_name(ros_type: str) -> str:
    """``std_msgs/msg/String`` → ``std_msgs::msg::dds_::String_`` (idempotent on DDS names)."""
    if "::" in ros_type:
        return ros_type
    parts = ros_type.split("/")
    if len(parts) != 3 or not all(parts):
        raise ValueError(f"invalid type name {ros_type!r}: expected 'pkg/msg|srv|action/Name'")
    pkg, kind, name = parts
    if kind not in ("msg", "srv", "action"):
        raise ValueError(f"invalid type name {ros_type!r}: middle part must be msg, srv or action")
    return f"{pkg}::{kind}::dds_::{name}_"


def ros_type_name(dds_type: str) -> str:
    """``std_msgs::msg::dds_::String_`` → ``std_msgs/msg/String`` (idempotent on ROS names)."""
    if "::" not in dds_type:
        return dds_type
    parts = dds_type.split("::")
    if "dds_" in parts:
        parts.remove("dds_")
        if parts[-1].endswith("_"):
            parts[-1] = parts[-1][:-1]
    return "/".join(parts)


def topic_key(domain_id: int, fq_name: str, type_name: str, type_hash: str) -> str:
    """The data key expression: ``<domain>/<name without outer '/'>/<dds type>/<hash>``."""
    name = fq_name[1:] if fq_name.startswith("/") else fq_name
    name = name[:-1] if name.endswith("/") else name
    if not name:
        raise ValueError(f"invalid topic name {fq_name!r} for a key expression")
    if not type_hash:
        raise ValueError("type hash must not be empty")
    return f"{int(domain_id)}/{name}/{dds_type_name(type_name)}/{type_hash}"


def mangle(name: str) -> str:
    """Make a name one key chunk: every '/' becomes '%'."""
    return name.replace("/", "%")


def demangle(chunk: str) -> str:
    """A name chunk of a key or token back to the ROS name ('%' → '/')."""
    return chunk.replace("%", "/")


def liveliness_prefix(domain_id: int) -> str:
    """The liveliness key prefix of a domain."""
    return f"{LIVELINESS_PREFIX}/{int(domain_id)}"


def liveliness_subscription_key(domain_id: int | None) -> str:
    """What to subscribe/get for graph discovery (None: every domain); ``@ros2_lv`` is
    hermetic so ``**`` alone won't."""
    return f"{LIVELINESS_PREFIX if domain_id is None else liveliness_prefix(domain_id)}/**"


class EntityKind(str, enum.Enum):
    """The kind of a liveliness token (rmw_zenoh's two-letter codes)."""

    NODE = "NN"
    PUBLISHER = "MP"
    SUBSCRIPTION = "MS"
    SERVICE = "SS"
    CLIENT = "SC"


def _chunk(value: str, what: str) -> str:
    if not value:
        raise ValueError(f"liveliness token {what} must not be empty")
    return mangle(value)


def node_token(
    domain_id: int, zid: str, nid: int, namespace: str, node_name: str, enclave: str = "/"
) -> str:
    """The NN token; the entity-id field repeats the node id."""
    return "/".join(
        [
            liveliness_prefix(domain_id),
            _chunk(zid, "zid"),
            str(nid),
            str(nid),
            EntityKind.NODE.value,
            _chunk(enclave, "enclave"),
            _chunk(namespace, "namespace"),
            _chunk(node_name, "node name"),
        ]
    )


def endpoint_token(
    domain_id: int,
    zid: str,
    nid: int,
    eid: int,
    kind: EntityKind | str,
    namespace: str,
    node_name: str,
    topic_name: str,
    type_name: str,
    type_hash: str,
    qos: QoSProfile,
    enclave: str = "/",
) -> str:
    """An MP/MS/SS/SC token.  ``topic_name`` is the full name; ``type_name`` ROS or DDS form."""
    kind = EntityKind(kind)
    if kind is EntityKind.NODE:
        raise ValueError("use node_token() for NN tokens")
    return "/".join(
        [
            liveliness_prefix(domain_id),
            _chunk(zid, "zid"),
            str(nid),
            str(eid),
            kind.value,
            _chunk(enclave, "enclave"),
            _chunk(namespace, "namespace"),
            _chunk(node_name, "node name"),
            _chunk(topic_name, "topic name"),
            _chunk(dds_type_name(type_name), "type"),
            _chunk(type_hash, "type hash"),
            encode_qos(qos),
        ]
    )


@dataclass(frozen=True)
class Entity:
    """One parsed liveliness token: a node, or an endpoint with its topic, type and QoS."""

    domain_id: int
    zid: str
    nid: int
    eid: int
    kind: EntityKind
    enclave: str
    namespace: str
    node_name: str
    topic_name: str | None = None
    type_name: str | None = None  # ROS form, e.g. std_msgs/msg/String
    dds_type_name: str | None = None
    type_hash: str | None = None
    qos: QoSProfile | None = None
    qos_chunk: str | None = None
    extra: tuple[str, ...] = ()  # e.g. Rolling's optional 14th "backends" chunk

    @property
    def node_fqn(self) -> str:
        """'/namespace/name' of the node owning the entity."""
        return node_fqn(self.namespace, self.node_name)

    @property
    def is_node(self) -> bool:
        """Whether the token stands for a node (not one of its endpoints)."""
        return self.kind is EntityKind.NODE

    def to_token(self) -> str:
        """Rebuild the token (without ``extra``); handy for GIDs and tests."""
        if self.kind is EntityKind.NODE:
            return node_token(
                self.domain_id, self.zid, self.nid, self.namespace, self.node_name, self.enclave
            )
        assert self.topic_name and self.type_hash and self.qos_chunk is not None
        base = "/".join(
            [
                liveliness_prefix(self.domain_id),
                self.zid,
                str(self.nid),
                str(self.eid),
                self.kind.value,
                mangle(self.enclave),
                mangle(self.namespace),
                mangle(self.node_name),
                mangle(self.topic_name),
                mangle(self.dds_type_name or dds_type_name(self.type_name or "")),
                mangle(self.type_hash),
                self.qos_chunk,
            ]
        )
        return base


# Graphs repeat a handful of QoS chunks across thousands of tokens and profiles are frozen,
# so decoding each distinct chunk once makes a big graph snapshot noticeably cheaper.
_decode_qos_cached = functools.lru_cache(maxsize=1024)(decode_qos)


def _fail(strict: bool, key: str, why: str) -> None:
    if strict:
        raise ValueError(f"not an rmw_zenoh liveliness token ({why}): {key!r}")


_KINDS = {kind.value: kind for kind in EntityKind}
_ros_type_name_cached = functools.lru_cache(maxsize=1024)(ros_type_name)
_new = object.__new__


def _entity(fields: dict[str, object]) -> Entity:
    """An Entity from all its fields, without the frozen dataclass's per-field
    ``object.__setattr__`` (a big graph snapshot makes thousands)."""
    entity: Entity = _new(Entity)
    entity.__dict__.update(fields)
    return entity


def parse_token(key: str, *, strict: bool = False) -> Entity | None:
    """Parse an ``@ros2_lv`` key into an :class:`Entity`.

    Returns ``None`` for anything that is not a well-formed token (or raises ``ValueError``
    with the reason when ``strict``).  Extra trailing chunks are kept in ``Entity.extra``;
    a QoS chunk that does not decode leaves ``qos=None`` unless ``strict``.
    """
    key = str(key)
    if "\n" in key:
        # no ROS name, type, hash or QoS number holds one, and wherever names travel one a
        # line (the daemon's answer, `node list` piped) it would forge a second entry
        _fail(strict, key, "a newline in the key")
        return None
    parts = key.split("/")
    if len(parts) < 9 or parts[0] != LIVELINESS_PREFIX:
        _fail(strict, key, "wrong prefix or too few chunks")
        return None
    try:
        domain_id, nid, eid = int(parts[1]), int(parts[3]), int(parts[4])
    except ValueError:
        _fail(strict, key, "domain, node id and entity id must be integers")
        return None
    kind = _KINDS.get(parts[5])
    if kind is None:
        _fail(strict, key, f"unknown entity kind {parts[5]!r}")
        return None
    if "" in parts[:9]:
        _fail(strict, key, "empty chunk")
        return None
    fields: dict[str, object] = {
        "domain_id": domain_id,
        "zid": parts[2],
        "nid": nid,
        "eid": eid,
        "kind": kind,
        "enclave": parts[6].replace("%", "/"),
        "namespace": parts[7].replace("%", "/"),
        "node_name": parts[8].replace("%", "/"),
        "topic_name": None,
        "type_name": None,
        "dds_type_name": None,
        "type_hash": None,
        "qos": None,
        "qos_chunk": None,
    }
    if kind is EntityKind.NODE:
        fields["extra"] = tuple(parts[9:])
        return _entity(fields)
    if len(parts) < 13 or "" in parts[9:12]:
        _fail(strict, key, "endpoint tokens need topic, type, hash and QoS chunks")
        return None
    dds = parts[10].replace("%", "/")
    qos: QoSProfile | None
    try:
        qos = _decode_qos_cached(parts[12])
    except (ValueError, OverflowError):
        if strict:
            raise
        qos = None
    fields["topic_name"] = parts[9].replace("%", "/")
    fields["type_name"] = _ros_type_name_cached(dds)
    fields["dds_type_name"] = dds
    fields["type_hash"] = parts[11].replace("%", "/")
    fields["qos"] = qos
    fields["qos_chunk"] = parts[12]
    fields["extra"] = tuple(parts[13:])
    return _entity(fields)
