"""tf2's QoS for `/tf` and `/tf_static`, one place for every listener, broadcaster and tool.

`/tf` is ordinary reliable volatile traffic; `/tf_static` is transient local, so a listener
that starts late still gets every static transform (the broadcaster keeps its last message,
which carries all of them).
"""

from __future__ import annotations

from ros2lite.qos import DurabilityPolicy, HistoryPolicy, QoSProfile

__all__ = [
    'TF_STATIC_TOPIC',
    'TF_TOPIC',
    'dynamic_broadcaster_qos',
    'dynamic_listener_qos',
    'static_broadcaster_qos',
    'static_listener_qos',
]

TF_TOPIC = '/tf'
TF_STATIC_TOPIC = '/tf_static'


def dynamic_listener_qos(depth: int = 100) -> QoSProfile:
    """A `/tf` subscription's profile (tf2_ros's DynamicListenerQoS)."""
    return QoSProfile(
        depth=depth, durability=DurabilityPolicy.VOLATILE, history=HistoryPolicy.KEEP_LAST
    )


def dynamic_broadcaster_qos(depth: int = 100) -> QoSProfile:
    """A `/tf` publisher's profile (tf2_ros's DynamicBroadcasterQoS)."""
    return QoSProfile(depth=depth)


def static_listener_qos(depth: int = 100) -> QoSProfile:
    """A `/tf_static` subscription's profile (tf2_ros's StaticListenerQoS)."""
    return QoSProfile(
        depth=depth, durability=DurabilityPolicy.TRANSIENT_LOCAL, history=HistoryPolicy.KEEP_LAST
    )


def static_broadcaster_qos(depth: int = 1) -> QoSProfile:
    """A `/tf_static` publisher's profile (tf2_ros's StaticBroadcasterQoS)."""
    return QoSProfile(
        depth=depth, durability=DurabilityPolicy.TRANSIENT_LOCAL, history=HistoryPolicy.KEEP_LAST
    )
