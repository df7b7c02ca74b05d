"""How bags adapt QoS, both rules side by side as rosbag2 keeps them.

Recording asks for the strongest reliability/durability that every publisher of a topic
offers (so it connects to all of them); playing offers what the recorded publishers offered
when they all agreed, and rosbag2's default offer when they did not. Both warn when offers
are mixed, since that is when data (latched samples, reliability) can be lost. A
`--qos-profile-overrides-path` file replaces either choice per topic.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from pathlib import Path

from ros2lite.bag.errors import BagError, MetadataError
from ros2lite.bag.metadata import qos_from_dict, qos_to_dict
from ros2lite.qos import HistoryPolicy, QoSProfile, match_publishers_qos
from ros2lite.util.files import ReadRefused, read_text_bounded
from ros2lite.util.safe_yaml import YamlInputError, load

__all__ = [
    "QoSOverrideError",
    "parse_qos_overrides",
    "playback_qos",
    "read_qos_overrides",
    "recording_qos",
]

Warn = Callable[[str], object]


class QoSOverrideError(MetadataError):
    """A QoS override file that cannot be used; the message says what is wrong."""


def recording_qos(
    topic: str, offered: Sequence[QoSProfile], warn: Warn | None = None
) -> QoSProfile:
    """What the recorder asks for: reliable / transient local only when every publisher
    offers it (:func:`ros2lite.qos.match_publishers_qos`), and KEEP_ALL (as deep as the
    deepest offer) so Zenoh queues rather than drops while the writer catches up."""
    depth = max([q.depth for q in offered] + [1])
    matched = match_publishers_qos(QoSProfile(history=HistoryPolicy.KEEP_ALL, depth=depth), offered)
    if warn is not None and matched.reliability_fell_back:
        warn(
            f"Publishers of '{topic}' differ in reliability: recording best effort so that "
            "all of them connect (messages of the reliable ones may be dropped)"
        )
    if warn is not None and matched.durability_fell_back:
        warn(
            f"Publishers of '{topic}' differ in durability: recording volatile so that all "
            "of them connect (samples they published earlier are not retrieved)"
        )
    return matched.profile


def _same_offer(a: QoSProfile, b: QoSProfile) -> bool:
    """Equal in every policy that decides compatibility (history and lifespan do not)."""
    return (
        a.reliability == b.reliability
        and a.durability == b.durability
        and a.deadline == b.deadline
        and a.liveliness == b.liveliness
        and a.liveliness_lease_duration == b.liveliness_lease_duration
    )


def playback_qos(
    topic: str, recorded: Sequence[QoSProfile], warn: Warn | None = None
) -> QoSProfile:
    """What the player offers: the recorded publishers' offer when they all made the same
    one (keep-last at least 10 deep; keep-all when every one of them kept all, so Zenoh
    blocks rather than drops, as it did for the originals); rosbag2's default offer
    (reliable, volatile, keep-last 10) when they differed, with a warning."""
    if not recorded:
        return QoSProfile(depth=10)
    first = recorded[0]
    if not all(_same_offer(first, q) for q in recorded[1:]):
        if warn is not None:
            warn(
                f"Publishers of '{topic}' were recorded with different QoS offers; playing "
                "it with the default offer (reliable, volatile, keep last 10)"
            )
        return QoSProfile(depth=10)
    keep_all = all(q.history == HistoryPolicy.KEEP_ALL for q in recorded)
    return QoSProfile(
        reliability=first.reliability,
        durability=first.durability,
        history=HistoryPolicy.KEEP_ALL if keep_all else HistoryPolicy.KEEP_LAST,
        depth=max([10] + [q.depth for q in recorded]),
        deadline=first.deadline,
        liveliness=first.liveliness,
        liveliness_lease_duration=first.liveliness_lease_duration,
    )


def read_qos_overrides(path: str | Path) -> dict[str, QoSProfile]:
    """The overrides file at `path` (see :func:`parse_qos_overrides`)."""
    try:
        text = read_text_bounded(path, "a QoS overrides file")
    except ReadRefused as e:
        raise BagError(f"Cannot read '{path}': {e.reason}") from None
    return parse_qos_overrides(text)


# a queue's length in a C ssize_t on any platform, as every other count option
_MAX_DEPTH = 2**31 - 1

_QOS_KEYS = {
    "history",
    "depth",
    "reliability",
    "durability",
    "deadline",
    "lifespan",
    "liveliness",
    "liveliness_lease_duration",
    "avoid_ros_namespace_conventions",
}


def parse_qos_overrides(text: str) -> dict[str, QoSProfile]:
    """A `--qos-profile-overrides-path` file: topic name → profile (names or numbers for the
    policies; durations as {sec, nsec}). Keys left out keep rclpy's defaults."""
    try:
        doc = load(text, "QoS override file")
    except YamlInputError as e:
        raise QoSOverrideError(str(e)) from None
    if doc is None:
        return {}
    if not isinstance(doc, dict):
        raise QoSOverrideError("QoS override file must map topic names to profiles")
    out: dict[str, QoSProfile] = {}
    defaults = QoSProfile(depth=10)
    for topic, profile in doc.items():
        if not isinstance(profile, dict):
            raise QoSOverrideError(f"QoS override of {topic!r} must be a mapping")
        for key in profile:
            if key not in _QOS_KEYS:
                raise QoSOverrideError(f"Unexpected key `{key}` for QoS profile.")
        for key in ("deadline", "lifespan", "liveliness_lease_duration"):
            value = profile.get(key)
            if value is not None and (not isinstance(value, dict) or set(value) != {"sec", "nsec"}):
                raise QoSOverrideError(f"QoS override {key} of {topic!r} needs both sec and nsec")
        depth = profile.get("depth")
        if depth is not None and (
            isinstance(depth, bool) or not isinstance(depth, int) or not 0 <= depth <= _MAX_DEPTH
        ):
            # a depth of 1e20 ended the recorder's queue set-up, recording nothing
            raise QoSOverrideError(
                f"QoS override depth of {topic!r} must be an integer in 0..{_MAX_DEPTH}, "
                f"got {depth!r}"
            )
        full = {**qos_to_dict(defaults, True), **profile}
        out[str(topic)] = qos_from_dict(full)
    return out
