"""rmw_zenoh's encoding of QoS: the liveliness-token chunk and rmw_zenoh's defaults.

Zenoh itself does not match endpoints by QoS; the QoS only travels in the liveliness token
(so ``topic info -v`` can show it) and selects how an endpoint is declared (TRANSIENT_LOCAL
→ advanced publisher/subscriber). The profiles themselves are :mod:`ros2lite.qos`'.
"""

from __future__ import annotations

from ros2lite.duration import Duration
from ros2lite.qos import (
    DURATION_INFINITE,
    DurabilityPolicy,
    HistoryPolicy,
    LivelinessPolicy,
    QoSProfile,
    ReliabilityPolicy,
)

__all__ = [
    "ZENOH_DEFAULT_QOS",
    "best_available_qos",
    "decode_qos",
    "encode_qos",
]

_R, _D, _H, _L = ReliabilityPolicy, DurabilityPolicy, HistoryPolicy, LivelinessPolicy

#: What rmw_zenoh writes as "empty" in a token: RELIABLE, VOLATILE, KEEP_LAST 42, infinite.
ZENOH_DEFAULT_QOS = QoSProfile(
    reliability=_R.RELIABLE,
    durability=_D.VOLATILE,
    history=_H.KEEP_LAST,
    depth=42,
    deadline=DURATION_INFINITE,
    lifespan=DURATION_INFINITE,
    liveliness=_L.AUTOMATIC,
    liveliness_lease_duration=DURATION_INFINITE,
)


def best_available_qos(profile: QoSProfile) -> QoSProfile:
    """Normalise a requested profile exactly like rmw_zenoh before it is used or advertised.

    SYSTEM_DEFAULT picks rmw_zenoh's default, depth 0 becomes 42 and unspecified durations
    become infinite.  BEST_AVAILABLE policies are left as they are (rmw_zenoh advertises
    them unresolved); use :func:`resolve_best_available` to pick concrete values.
    """
    d = ZENOH_DEFAULT_QOS
    for field, unknown in (
        ("reliability", _R.UNKNOWN),
        ("durability", _D.UNKNOWN),
        ("history", _H.UNKNOWN),
        ("liveliness", _L.UNKNOWN),
    ):
        if getattr(profile, field) == unknown:
            raise ValueError(f"QoS {field} UNKNOWN is not supported")
    return QoSProfile(
        reliability=d.reliability
        if profile.reliability == _R.SYSTEM_DEFAULT
        else profile.reliability,
        durability=d.durability if profile.durability == _D.SYSTEM_DEFAULT else profile.durability,
        history=d.history if profile.history == _H.SYSTEM_DEFAULT else profile.history,
        depth=d.depth if profile.depth == 0 else profile.depth,
        deadline=d.deadline if profile.deadline.is_unspecified else profile.deadline,
        lifespan=d.lifespan if profile.lifespan.is_unspecified else profile.lifespan,
        liveliness=d.liveliness if profile.liveliness == _L.SYSTEM_DEFAULT else profile.liveliness,
        liveliness_lease_duration=(
            d.liveliness_lease_duration
            if profile.liveliness_lease_duration.is_unspecified
            else profile.liveliness_lease_duration
        ),
    )


# rmw_zenoh reads every number of a QoS chunk as an unsigned 64-bit value
_UINT64_MAX = 2**64 - 1
_INFINITE_NS = 2**63 - 1


def _rmw_time(sec: int, nsec: int) -> Duration:
    """A token's duration: rmw_zenoh takes any uint64 seconds and nanoseconds, while a
    Duration holds at most rmw's infinity (INT64_MAX ns), so longer ones are infinite."""
    return Duration(nanoseconds=min(sec * 1_000_000_000 + nsec, _INFINITE_NS))


def _num(value: int, default: int) -> str:
    return "" if value == default else str(int(value))


def encode_qos(profile: QoSProfile, *, normalise: bool = True) -> str:
    """The token QoS chunk, e.g. ``::,10:,:,:,,`` for ``QoSProfile(depth=10)``.

    Each number is written only when it differs from rmw_zenoh's default.  The profile is
    first normalised with :func:`best_available_qos` (as rmw_zenoh does) unless told not to.
    """
    q = best_available_qos(profile) if normalise else profile
    d = ZENOH_DEFAULT_QOS
    return (
        f"{_num(q.reliability, d.reliability)}:"
        f"{_num(q.durability, d.durability)}:"
        f"{_num(q.history, d.history)},{_num(q.depth, d.depth)}:"
        f"{_num(q.deadline.sec, d.deadline.sec)},{_num(q.deadline.nsec, d.deadline.nsec)}:"
        f"{_num(q.lifespan.sec, d.lifespan.sec)},{_num(q.lifespan.nsec, d.lifespan.nsec)}:"
        f"{_num(q.liveliness, d.liveliness)},"
        f"{_num(q.liveliness_lease_duration.sec, d.liveliness_lease_duration.sec)},"
        f"{_num(q.liveliness_lease_duration.nsec, d.liveliness_lease_duration.nsec)}"
    )


def _parse_int(text: str, default: int, what: str, chunk: str) -> int:
    text = text.strip()
    if not text:
        return default
    try:
        value = int(text)
    except ValueError:
        raise ValueError(f"bad {what} {text!r} in QoS chunk {chunk!r}") from None
    if value > _UINT64_MAX:
        raise ValueError(f"{what} {text!r} in QoS chunk {chunk!r} exceeds 64 bits")
    return value


def decode_qos(
    chunk: str, *, default_durability: DurabilityPolicy = DurabilityPolicy.VOLATILE
) -> QoSProfile:
    """Parse a token QoS chunk back into a profile.

    Lenient on purpose: missing trailing fields take the defaults, and an empty durability
    decodes as ``default_durability``.  Old peers (Jazzy 0.2.0-0.2.2) defaulted to
    TRANSIENT_LOCAL and left it empty; callers that know they face such a peer pass
    ``default_durability=DurabilityPolicy.TRANSIENT_LOCAL``.  An explicit ``2`` always
    decodes as VOLATILE.  Raises ``ValueError`` on non-numeric or out-of-range values.
    """
    d = ZENOH_DEFAULT_QOS
    parts = chunk.split(":")
    if len(parts) < 3 or len(parts) > 6:
        raise ValueError(f"QoS chunk {chunk!r} must have 3 to 6 ':'-separated fields")
    parts += [""] * (6 - len(parts))

    def sub(index: int, count: int) -> list[str]:
        values = parts[index].split(",")
        if len(values) > count:
            raise ValueError(f"too many ',' values in field {index} of QoS chunk {chunk!r}")
        return values + [""] * (count - len(values))

    hist, depth = sub(2, 2)
    dl_s, dl_ns = sub(3, 2)
    ls_s, ls_ns = sub(4, 2)
    liv, lease_s, lease_ns = sub(5, 3)
    try:
        return QoSProfile(
            reliability=ReliabilityPolicy(
                _parse_int(parts[0], d.reliability, "reliability", chunk)
            ),
            durability=DurabilityPolicy(
                _parse_int(parts[1], default_durability, "durability", chunk)
            ),
            history=HistoryPolicy(_parse_int(hist, d.history, "history", chunk)),
            depth=_parse_int(depth, d.depth, "depth", chunk),
            deadline=_rmw_time(
                _parse_int(dl_s, d.deadline.sec, "deadline", chunk),
                _parse_int(dl_ns, d.deadline.nsec, "deadline", chunk),
            ),
            lifespan=_rmw_time(
                _parse_int(ls_s, d.lifespan.sec, "lifespan", chunk),
                _parse_int(ls_ns, d.lifespan.nsec, "lifespan", chunk),
            ),
            liveliness=LivelinessPolicy(_parse_int(liv, d.liveliness, "liveliness", chunk)),
            liveliness_lease_duration=_rmw_time(
                _parse_int(lease_s, d.liveliness_lease_duration.sec, "lease", chunk),
                _parse_int(lease_ns, d.liveliness_lease_duration.nsec, "lease", chunk),
            ),
        )
    except ValueError as exc:
        if "QoS chunk" in str(exc):
            raise
        raise ValueError(f"bad value in QoS chunk {chunk!r}: {exc}") from None
