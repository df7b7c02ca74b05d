"""Quality of service as rclpy has it: profiles, policies, presets and compatibility.

The concept lives here; :mod:`ros2lite.transport.qos` only encodes profiles into liveliness
tokens and picks how an endpoint is declared from them. Enum values are rmw's
(``rmw/types.h``) because those are the numbers written into tokens and bags.
"""

from __future__ import annotations

import dataclasses
import enum
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from typing import NamedTuple, TypeVar

from ros2lite.duration import Duration

__all__ = [
    "DURATION_BEST_AVAILABLE",
    "DURATION_INFINITE",
    "DURATION_UNSPECIFIED",
    "PRESETS",
    "Compatibility",
    "DurabilityPolicy",
    "Duration",
    "HistoryPolicy",
    "LivelinessPolicy",
    "MatchedQoS",
    "QoSDurabilityPolicy",
    "QoSHistoryPolicy",
    "QoSLivelinessPolicy",
    "QoSPresetProfiles",
    "QoSProfile",
    "QoSReliabilityPolicy",
    "ReliabilityPolicy",
    "check_compatible",
    "match_publishers_qos",
    "preset",
    "qos_profile_action_status_default",
    "qos_profile_best_available",
    "qos_profile_default",
    "qos_profile_parameter_events",
    "qos_profile_parameters",
    "qos_profile_rosout_default",
    "qos_profile_sensor_data",
    "qos_profile_services_default",
    "qos_profile_system_default",
    "qos_profile_unknown",
    "resolve_best_available",
]

_P = TypeVar("_P", bound="_Policy")


class _Policy(enum.IntEnum):
    """An rmw policy enum that also knows ros2cli's lower-case spelling (``best_effort``)."""

    @property
    def short_key(self) -> str:
        return self.name.lower()

    @classmethod
    def from_short_key(cls: type[_P], text: str) -> _P:
        key = text.strip().lower().replace("-", "_")
        for member in cls:
            if member.short_key == key:
                return member
        choices = ", ".join(m.short_key for m in cls)
        raise ValueError(f"invalid {cls.__name__} {text!r}; choose one of: {choices}")

    @classmethod
    def short_keys(cls) -> list[str]:
        return [m.short_key for m in cls]


class ReliabilityPolicy(_Policy):
    """Whether delivery is retried (RELIABLE) or may drop (BEST_EFFORT)."""

    SYSTEM_DEFAULT = 0
    RELIABLE = 1
    BEST_EFFORT = 2
    UNKNOWN = 3
    BEST_AVAILABLE = 4


class DurabilityPolicy(_Policy):
    """Whether late subscribers get earlier samples (TRANSIENT_LOCAL)."""

    SYSTEM_DEFAULT = 0
    TRANSIENT_LOCAL = 1
    VOLATILE = 2
    UNKNOWN = 3
    BEST_AVAILABLE = 4


class HistoryPolicy(_Policy):
    """Whether `depth` bounds the queue (KEEP_LAST) or not (KEEP_ALL)."""

    SYSTEM_DEFAULT = 0
    KEEP_LAST = 1
    KEEP_ALL = 2
    UNKNOWN = 3


class LivelinessPolicy(_Policy):
    """How an endpoint shows it is alive."""

    SYSTEM_DEFAULT = 0
    AUTOMATIC = 1
    MANUAL_BY_NODE = 2  # deprecated in rmw, kept so old tokens still decode
    MANUAL_BY_TOPIC = 3
    UNKNOWN = 4
    BEST_AVAILABLE = 5


DURATION_UNSPECIFIED = Duration()
DURATION_INFINITE = Duration(nanoseconds=2**63 - 1)  # rmw's {INT64_MAX ns}
DURATION_BEST_AVAILABLE = Duration(nanoseconds=2**63 - 2)


@dataclass(frozen=True)
class QoSProfile:
    """A QoS profile with rclpy's field names and defaults (reliable, volatile, keep_last 10).

    Durations left at 0 mean "unspecified", as in rmw; the transport turns them into the
    infinite value rmw_zenoh puts in tokens.
    """

    reliability: ReliabilityPolicy = ReliabilityPolicy.RELIABLE
    durability: DurabilityPolicy = DurabilityPolicy.VOLATILE
    history: HistoryPolicy = HistoryPolicy.KEEP_LAST
    depth: int = 10
    deadline: Duration = DURATION_UNSPECIFIED
    lifespan: Duration = DURATION_UNSPECIFIED
    liveliness: LivelinessPolicy = LivelinessPolicy.SYSTEM_DEFAULT
    liveliness_lease_duration: Duration = DURATION_UNSPECIFIED

    def __post_init__(self) -> None:
        # Accept plain ints (e.g. from YAML or tokens) but store the enums.
        object.__setattr__(self, "reliability", ReliabilityPolicy(self.reliability))
        object.__setattr__(self, "durability", DurabilityPolicy(self.durability))
        object.__setattr__(self, "history", HistoryPolicy(self.history))
        object.__setattr__(self, "liveliness", LivelinessPolicy(self.liveliness))
        if self.depth < 0:
            raise ValueError(f"QoS depth must not be negative: {self.depth}")
        for name in ("deadline", "lifespan", "liveliness_lease_duration"):
            if getattr(self, name).nanoseconds < 0:
                raise ValueError(f"QoS {name.replace('_', ' ')} must not be negative")

    def replace(self, **changes: object) -> QoSProfile:
        """A copy with some fields changed (``dataclasses.replace`` under a friendlier name)."""
        return dataclasses.replace(self, **changes)  # type: ignore[arg-type]

    @property
    def is_transient_local(self) -> bool:
        """Whether late subscribers get the last samples."""
        return self.durability == DurabilityPolicy.TRANSIENT_LOCAL


# rclpy's older spellings of the policy enums
QoSReliabilityPolicy = ReliabilityPolicy
QoSDurabilityPolicy = DurabilityPolicy
QoSHistoryPolicy = HistoryPolicy
QoSLivelinessPolicy = LivelinessPolicy


_R, _D, _H, _L = ReliabilityPolicy, DurabilityPolicy, HistoryPolicy, LivelinessPolicy

qos_profile_default = QoSProfile()
qos_profile_sensor_data = QoSProfile(reliability=_R.BEST_EFFORT, depth=5)
qos_profile_system_default = QoSProfile(
    reliability=_R.SYSTEM_DEFAULT,
    durability=_D.SYSTEM_DEFAULT,
    history=_H.SYSTEM_DEFAULT,
    depth=0,
)
qos_profile_services_default = QoSProfile()
qos_profile_parameters = QoSProfile(depth=1000)
qos_profile_parameter_events = QoSProfile(depth=1000)
qos_profile_rosout_default = QoSProfile(
    durability=_D.TRANSIENT_LOCAL, depth=1000, lifespan=Duration(seconds=10)
)
qos_profile_action_status_default = QoSProfile(durability=_D.TRANSIENT_LOCAL, depth=1)
qos_profile_best_available = QoSProfile(
    reliability=_R.BEST_AVAILABLE,
    durability=_D.BEST_AVAILABLE,
    depth=10,
    deadline=DURATION_BEST_AVAILABLE,
    liveliness=_L.BEST_AVAILABLE,
    liveliness_lease_duration=DURATION_BEST_AVAILABLE,
)
qos_profile_unknown = QoSProfile(
    reliability=_R.UNKNOWN,
    durability=_D.UNKNOWN,
    history=_H.UNKNOWN,
    depth=0,
    liveliness=_L.UNKNOWN,
)

#: Presets by the short names ros2cli's ``--qos-profile`` accepts (plus a few rcl ones).
PRESETS: dict[str, QoSProfile] = {
    "unknown": qos_profile_unknown,
    "system_default": qos_profile_system_default,
    "sensor_data": qos_profile_sensor_data,
    "services_default": qos_profile_services_default,
    "parameters": qos_profile_parameters,
    "parameter_events": qos_profile_parameter_events,
    "action_status_default": qos_profile_action_status_default,
    "best_available": qos_profile_best_available,
    "rosout_default": qos_profile_rosout_default,
    "default": qos_profile_default,
}


class QoSPresetProfiles(enum.Enum):
    """rclpy's enum of the presets: ``QoSPresetProfiles.SENSOR_DATA.value`` is the profile."""

    UNKNOWN = qos_profile_unknown
    SYSTEM_DEFAULT = qos_profile_system_default
    SENSOR_DATA = qos_profile_sensor_data
    SERVICES_DEFAULT = qos_profile_services_default
    PARAMETERS = qos_profile_parameters
    PARAMETER_EVENTS = qos_profile_parameter_events
    ACTION_STATUS_DEFAULT = qos_profile_action_status_default
    BEST_AVAILABLE = qos_profile_best_available

    @classmethod
    def short_keys(cls) -> list[str]:
        """The presets' names as the CLI spells them."""
        return [name.lower() for name in cls.__members__]  # aliases too (equal profiles)

    @classmethod
    def get_from_short_key(cls, name: str) -> QoSProfile:
        """The preset profile of a CLI name."""
        return cls[name.upper()].value


def preset(name: str) -> QoSProfile:
    """Look up a preset by its short name (``sensor_data``) or rclpy name (``qos_profile_…``)."""
    key = name.strip().lower().replace("-", "_")
    key = key.removeprefix("qos_profile_")
    try:
        return PRESETS[key]
    except KeyError:
        choices = ", ".join(PRESETS)
        raise ValueError(f"unknown QoS profile {name!r}; choose one of: {choices}") from None


def _no_duration(d: Duration) -> bool:
    # rmw compares with {0,0}; tokens carry "infinite" instead, which means the same thing.
    return d.is_unspecified or d.is_infinite


def resolve_best_available(
    profile: QoSProfile, others: Sequence[QoSProfile], *, for_publisher: bool
) -> QoSProfile:
    """Replace BEST_AVAILABLE policies using the other side's profiles (rmw_dds_common's rules).

    A publisher always takes RELIABLE and TRANSIENT_LOCAL (compatible with every
    subscription); a subscription takes the strongest policy all ``others`` (publishers) offer.
    """
    changes: dict[str, object] = {}
    n = len(others)
    if for_publisher:
        if profile.reliability == _R.BEST_AVAILABLE:
            changes["reliability"] = _R.RELIABLE
        if profile.durability == _D.BEST_AVAILABLE:
            changes["durability"] = _D.TRANSIENT_LOCAL
        if profile.liveliness == _L.BEST_AVAILABLE:
            manual = any(o.liveliness == _L.MANUAL_BY_TOPIC for o in others)
            changes["liveliness"] = _L.MANUAL_BY_TOPIC if manual else _L.AUTOMATIC
        pick = min
    else:
        if profile.reliability == _R.BEST_AVAILABLE:
            all_rel = sum(o.reliability == _R.RELIABLE for o in others) == n
            changes["reliability"] = _R.RELIABLE if all_rel else _R.BEST_EFFORT
        if profile.durability == _D.BEST_AVAILABLE:
            all_tl = sum(o.durability == _D.TRANSIENT_LOCAL for o in others) == n
            changes["durability"] = _D.TRANSIENT_LOCAL if all_tl else _D.VOLATILE
        if profile.liveliness == _L.BEST_AVAILABLE:
            all_man = sum(o.liveliness == _L.MANUAL_BY_TOPIC for o in others) == n
            changes["liveliness"] = _L.MANUAL_BY_TOPIC if all_man else _L.AUTOMATIC
        pick = max
    for field in ("deadline", "liveliness_lease_duration"):
        if getattr(profile, field) == DURATION_BEST_AVAILABLE:
            given = [getattr(o, field) for o in others if not _no_duration(getattr(o, field))]
            changes[field] = pick(given) if given else DURATION_UNSPECIFIED
    return dataclasses.replace(profile, **changes)  # type: ignore[arg-type]


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

    That is rmw"s BEST_AVAILABLE rule for a subscription (:func:`resolve_best_available`): the
    strongest request still compatible with all of them, and TRANSIENT_LOCAL is what
    receives a latched publisher"s history. A publisher whose QoS is unknown counts as the
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
    reliability=ReliabilityPolicy.BEST_EFFORT, durability=DurabilityPolicy.VOLATILE
)


class Compatibility(NamedTuple):
    """Result of :func:`check_compatible`; ``reason`` lists ERROR/WARNING lines, or is empty."""

    compatible: bool
    reason: str


def check_compatible(publisher: QoSProfile, subscription: QoSProfile) -> Compatibility:
    """Would a subscription with these requests get data from this publisher's offer?

    Follows rmw's request/offer rules (what ``rmw_qos_profile_check_compatible`` reports):
    errors make the pair incompatible, warnings (a side is SYSTEM_DEFAULT/UNKNOWN) do not.
    Unspecified and infinite deadlines/leases both count as "none".
    """
    errors: list[str] = []
    pub, sub = publisher, subscription
    if pub.reliability == _R.BEST_EFFORT and sub.reliability == _R.RELIABLE:
        errors.append("ERROR: Best effort publisher and reliable subscription;")
    if pub.durability == _D.VOLATILE and sub.durability == _D.TRANSIENT_LOCAL:
        errors.append("ERROR: Volatile publisher and transient local subscription;")
    if _no_duration(pub.deadline) and not _no_duration(sub.deadline):
        errors.append("ERROR: Subscription has a deadline, but publisher does not;")
    elif not _no_duration(sub.deadline) and sub.deadline < pub.deadline:
        errors.append("ERROR: Subscription deadline is less than publisher deadline;")
    if pub.liveliness == _L.AUTOMATIC and sub.liveliness == _L.MANUAL_BY_TOPIC:
        errors.append(
            "ERROR: Publisher's liveliness is automatic and subscription's is manual by topic;"
        )
    pl, sl = pub.liveliness_lease_duration, sub.liveliness_lease_duration
    if _no_duration(pl) and not _no_duration(sl):
        errors.append(
            "ERROR: Subscription has a liveliness lease duration, but publisher does not;"
        )
    elif not _no_duration(pl) and not _no_duration(sl) and sl < pl:
        errors.append("ERROR: Subscription liveliness lease duration is less than publisher;")
    if errors:
        return Compatibility(False, " ".join(errors))
    return Compatibility(True, " ".join(_warnings(pub, sub)))


def _warnings(pub: QoSProfile, sub: QoSProfile) -> list[str]:
    out: list[str] = []
    checks = (
        ("reliability", (_R.SYSTEM_DEFAULT, _R.UNKNOWN), _R.RELIABLE, _R.BEST_EFFORT),
        ("durability", (_D.SYSTEM_DEFAULT, _D.UNKNOWN), _D.TRANSIENT_LOCAL, _D.VOLATILE),
        ("liveliness", (_L.SYSTEM_DEFAULT, _L.UNKNOWN), _L.MANUAL_BY_TOPIC, _L.AUTOMATIC),
    )
    for field, unknown, strict_sub, weak_pub in checks:
        p, s = getattr(pub, field), getattr(sub, field)
        if p in unknown and s in unknown:
            out.append(
                f"WARNING: Publisher {field} is {p.short_key} and subscription {field} is "
                f"{s.short_key};"
            )
        elif p in unknown and s == strict_sub:
            out.append(
                f"WARNING: Subscription {field} is {s.short_key}, but publisher is {p.short_key};"
            )
        elif p == weak_pub and s in unknown:
            out.append(
                f"WARNING: Publisher {field} is {p.short_key}, but subscription is {s.short_key};"
            )
    return out
