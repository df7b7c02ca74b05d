"""Watching a topic from outside: find its type in the graph, pick a subscription QoS that
connects to every publisher, and see samples the moment they arrive.

Used by `topic echo/hz/bw/delay`; kept in the library because a script that monitors topics
needs the same three things.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Iterable
from typing import TYPE_CHECKING

from ros2lite.graph import Entity, EntityKind
from ros2lite.qos import QoSProfile
from ros2lite.subscription import MessageInfo, Subscription

if TYPE_CHECKING:
    from ros2lite.node import Node
    from ros2lite.transport.handles import Sample

__all__ = ['MonitoredSubscription', 'topic_types']


def topic_types(entities: Iterable[Entity], topic: str) -> list[str]:
    """Every type any endpoint (publisher or subscription) uses on `topic`, sorted."""
    return sorted(
        {
            e.type_name
            for e in entities
            if e.kind in (EntityKind.PUBLISHER, EntityKind.SUBSCRIPTION)
            and e.topic_name == topic
            and e.type_name
        }
    )


class MonitoredSubscription(Subscription):
    """A raw subscription that shows every sample to `on_arrival` the moment it arrives.

    `on_arrival(size, attachment, received_ns)` runs on the Zenoh thread before the sample
    is queued, with the CDR size, the rmw_zenoh attachment and the arrival time (the same
    clock as MessageInfo.received_timestamp). It therefore sees every sample, including the
    ones the subscription's queue (its QoS depth) drops when the consumer falls behind —
    which is where rmw_zenoh counts lost messages, and what lets `topic hz` stay exact at
    10 kHz. With `callback=None` nothing is queued at all: the hook is the whole consumer.

    `on_payload(cdr_bytes, attachment, received_ns)`, given instead of `on_arrival`, gets the
    payload itself on the same thread (what `bag record` keeps, never decoded).
    """

    def __init__(
        self,
        node: Node,
        msg_type: type | str,
        topic: str,
        callback: Callable[[bytes, MessageInfo], object] | None,
        qos: QoSProfile,
        *,
        on_arrival: Callable[[int, bytes, int], object] | None = None,
        on_payload: Callable[[bytes, bytes, int], object] | None = None,
    ) -> None:
        if (on_arrival is None) == (on_payload is None):
            raise TypeError('give exactly one of on_arrival and on_payload')
        self._on_arrival = on_arrival
        self._on_payload = on_payload
        self._deliver = callback is not None
        super().__init__(
            node, msg_type, topic, callback or _ignore, qos, raw=True, on_arrival=self._arrived
        )
        node.adopt(self)  # destroyed with the node, like its own ones

    def _arrived(self, sample: Sample) -> None:
        attachment = sample.attachment
        if attachment is None:
            return  # rmw_zenoh ignores samples without one
        if self._on_payload is not None:
            self._on_payload(sample.payload.to_bytes(), attachment.to_bytes(), time.time_ns())
        else:
            self._on_arrival(
                len(sample.payload),
                attachment.to_bytes(),  # type: ignore[misc]
                time.time_ns(),
            )
        if self._deliver:
            self._keep(sample)


def _ignore(*_: object) -> None:
    """Callback of a subscription whose samples are never queued."""
