"""The rmw_zenoh wire protocol: names, keys, tokens, QoS, attachments and session config.

This package moves bytes and names; it never imports message classes.  Importing it does
not import zenoh: :mod:`ros2lite.transport.config` (which does) is loaded on first use of
one of its names, so ``keys``/``qos``/``attachment`` stay cheap for the CLI.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from ros2lite.transport.attachment import (
    ATTACHMENT_SIZE,
    Attachment,
    decode_attachment,
    encode_attachment,
    gid_from_token,
)
from ros2lite.transport.keys import (
    Entity,
    EntityKind,
    dds_type_name,
    endpoint_token,
    expand_topic_name,
    liveliness_subscription_key,
    mangle,
    node_token,
    parse_token,
    ros_type_name,
    topic_key,
)
from ros2lite.transport.qos import (
    Compatibility,
    DurabilityPolicy,
    HistoryPolicy,
    LivelinessPolicy,
    QoSProfile,
    ReliabilityPolicy,
    check_compatible,
    decode_qos,
    encode_qos,
)

if TYPE_CHECKING:
    from ros2lite.transport.config import (
        ConfigError,
        RouterUnavailableError,
        SessionError,
        domain_id,
        open_session,
        router_config,
        router_endpoint,
        session_config,
    )

_CONFIG_NAMES = {
    "ConfigError",
    "RouterUnavailableError",
    "SessionError",
    "domain_id",
    "open_session",
    "router_config",
    "router_endpoint",
    "session_config",
}

__all__ = [
    "ATTACHMENT_SIZE",
    "Attachment",
    "Compatibility",
    "ConfigError",
    "DurabilityPolicy",
    "Entity",
    "EntityKind",
    "HistoryPolicy",
    "LivelinessPolicy",
    "QoSProfile",
    "ReliabilityPolicy",
    "RouterUnavailableError",
    "SessionError",
    "check_compatible",
    "dds_type_name",
    "decode_attachment",
    "decode_qos",
    "domain_id",
    "encode_attachment",
    "encode_qos",
    "endpoint_token",
    "expand_topic_name",
    "gid_from_token",
    "liveliness_subscription_key",
    "mangle",
    "node_token",
    "open_session",
    "parse_token",
    "ros_type_name",
    "router_config",
    "router_endpoint",
    "session_config",
    "topic_key",
]


def __getattr__(name: str) -> Any:
    if name in _CONFIG_NAMES:
        from ros2lite.transport import config

        return getattr(config, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
