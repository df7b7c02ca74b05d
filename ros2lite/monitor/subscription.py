"""Watching a topic from outside: find its type in the graph, pick a subscription QoS that
connects to every publisher, and see samples the moment they arrive.

Used by `topic echo/hz/bw/delay`; kept in the library because a script that monitors topics
needs the same three things.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Iterable
from dataclasses import dataclass
from typing import Any

from ros2lite.graph import Entity, EntityKind
from ros2lite.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy, resolve_best_available
from ros2lite.subscription import Subscription

__all__ = ['MatchedQoS', 'MonitoredSubscription', 'match_publishers_qos', 'topic_types']


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


@dataclass(frozen=True)
class MatchedQoS:
    """The profile to subscribe with, and which policies had to be weakened."""

    profile: QoSProfile
    reliability_fell_back: bool  # some but not all publishers are RELIABLE
    durability_fell_back: bool  # some but not all publishers are TRANSIENT_LOCAL


def match_publishers_qos(
    profile: QoSProfile, publishers: Iterable[QoSProfile | None]
) -> MatchedQoS:
    """Ask for RELIABLE / TRANSIENT_LOCAL only when every publisher offers it.

    That is rmw's BEST_AVAILABLE rule for a subscription (transport.qos owns it): the
    strongest request still compatible with all of them, and TRANSIENT_LOCAL is what
    receives a latched publisher's history. A publisher whose QoS is unknown counts as the
    weakest. With no publishers the profile is returned unchanged.
    """
    offered = [q if q is not None else _WEAKEST for q in publishers]
    if not offered:
        return MatchedQoS(profile, False, False)
    chosen = resolve_best_available(
        profile.replace(
            reliability=ReliabilityPolicy.BEST_AVAILABLE, durability=DurabilityPolicy.BEST_AVAILABLE
        ),
        offered,
        for_publisher=False,
    )
    n = len(offered)
    reliable = sum(q.reliability == ReliabilityPolicy.RELIABLE for q in offered)
    latched = sum(q.durability == DurabilityPolicy.TRANSIENT_LOCAL for q in offered)
    return MatchedQoS(chosen, 0 < reliable < n, 0 < latched < n)


_WEAKEST = QoSProfile(
    depth=10, reliability=ReliabilityPolicy.BEST_EFFORT, durability=DurabilityPolicy.VOLATILE
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
        node: Any,
        msg_type: Any,
        topic: str,
        callback: Callable[[bytes, Any], Any] | None,
        qos: QoSProfile,
        *,
        on_arrival: Callable[[int, bytes, int], Any] | None = None,
        on_payload: Callable[[bytes, bytes, int], Any] | None = None,
    ) -> None:
        if (on_arrival is None) == (on_payload is None):
            raise TypeError('give exactly one of on_arrival and on_payload')
        self._on_arrival = on_arrival
        self._on_payload = on_payload
        self._deliver = callback is not None
        super().__init__(node, msg_type, topic, callback or _ignore, qos, raw=True)
        node.subscriptions.append(self)  # destroyed with the node, like its own ones

    def _on_sample(self, sample: Any) -> None:
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
            super()._on_sample(sample)


def _ignore(*_: Any) -> None:
    """Callback of a subscription whose samples are never queued."""
