"""Senders of transforms: `/tf` for moving frames, `/tf_static` for fixed ones (tf2_ros's
TransformBroadcaster and StaticTransformBroadcaster)."""

from __future__ import annotations

from collections.abc import Iterable
from typing import TYPE_CHECKING

from ros2lite.msgs.geometry_msgs.msg import TransformStamped
from ros2lite.msgs.tf2_msgs.msg import TFMessage
from ros2lite.qos import QoSProfile
from ros2lite.tf2.qos import (
    TF_STATIC_TOPIC,
    TF_TOPIC,
    dynamic_broadcaster_qos,
    static_broadcaster_qos,
)

if TYPE_CHECKING:
    from ros2lite.node import Node

__all__ = ['StaticTransformBroadcaster', 'TransformBroadcaster']


def _as_list(transform: TransformStamped | Iterable[TransformStamped]) -> list[TransformStamped]:
    if isinstance(transform, TransformStamped):
        return [transform]
    return list(transform)


class TransformBroadcaster:
    """Publishes transforms of moving frames on `/tf`."""

    def __init__(self, node: Node, qos: QoSProfile | int | None = None) -> None:
        self.pub_tf = node.create_publisher(
            TFMessage, TF_TOPIC, dynamic_broadcaster_qos() if qos is None else qos
        )

    def sendTransform(self, transform: TransformStamped | Iterable[TransformStamped]) -> None:
        """Send one transform or several, in one message."""
        self.pub_tf.publish(TFMessage(transforms=_as_list(transform)))


class StaticTransformBroadcaster:
    """Publishes transforms of fixed frames on `/tf_static`, latched: every message carries
    all the frames this broadcaster has sent, so the one a late listener receives is whole."""

    def __init__(self, node: Node, qos: QoSProfile | int | None = None) -> None:
        self.pub_tf = node.create_publisher(
            TFMessage, TF_STATIC_TOPIC, static_broadcaster_qos() if qos is None else qos
        )
        self.net_message = TFMessage()
        self._index: dict[str, int] = {}

    def sendTransform(self, transform: TransformStamped | Iterable[TransformStamped]) -> None:
        """Add (or replace, by child frame) transforms, and publish them all."""
        transforms = self.net_message.transforms
        for t in _as_list(transform):
            at = self._index.get(t.child_frame_id)
            if at is None:
                self._index[t.child_frame_id] = len(transforms)
                transforms.append(t)
            else:
                transforms[at] = t
        self.pub_tf.publish(self.net_message)
