"""Quality of service as rclpy has it: profiles, policies, presets and compatibility.

The concept lives here; :mod:`ros2lite.transport.qos` only encodes profiles into liveliness
tokens and picks how an endpoint is declared from them. Enum values are rmw's
(``rmw/types.h``) because those are the numbers written into tokens and bags.
"""

from __future__ import annotations

import enum
import warnings
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from typing import NamedTuple, TypeVar

from ros2lite.duration import Duration
from ros2lite.exceptions import Ros2liteError

__all__ = [
    "DURATION_BEST_AVAILABLE",
    "DURATION_INFINITE",
    "DURATION_UNSPECIFIED",
    "PRESETS",
    "Compatibility",
    "DurabilityPolicy",
    "Duration",
    "HistoryPolicy",
    "InvalidQoSProfileException",
    "LivelinessPolicy",
    "MatchedQoS",
    "QoSCompatibility",
    "QoSDurabilityPolicy",
    "QoSHistoryPolicy",
    "QoSLivelinessPolicy",
    "QoSPolicyKind",
    "QoSPresetProfiles",
    "QoSProfile",
    "QoSReliabilityPolicy",
    "ReliabilityPolicy",
    "check_compatible",
    "incompatible_policy",
    "match_publishers_qos",
    "preset",
    "qos_check_compatible",
    "qos_policy_name_from_kind",
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
    "zenoh_check_compatible",
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

    @classmethod
    def get_from_short_key(cls: type[_P], name: str) -> int:
        """rclpy's lookup: the policy's number for a short key, any case."""
        return int(cls.from_short_key(name).value)


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


class InvalidQoSProfileException(Ros2liteError, ValueError):
    """A QoS profile that cannot be built (rclpy's name): no history or depth, or a
    negative depth or duration."""


_FIELDS = (
    "history",
    "depth",
    "reliability",
    "durability",
    "lifespan",
    "deadline",
    "liveliness",
    "liveliness_lease_duration",
    "avoid_ros_namespace_conventions",
)


class QoSProfile:
    """A QoS profile as rclpy has it: keyword arguments, `depth` and/or `history` required
    (depth alone means KEEP_LAST), reliable and volatile unless told otherwise; fields can
    be changed after construction.

    Durations left at 0 mean "unspecified", as in rmw; the transport turns them into the
    infinite value rmw_zenoh puts in tokens.
    """

    __slots__ = tuple("_" + f for f in _FIELDS)

    def __init__(
        self,
        *,
        history: HistoryPolicy | int | None = None,
        depth: int | None = None,
        reliability: ReliabilityPolicy | int = ReliabilityPolicy.RELIABLE,
        durability: DurabilityPolicy | int = DurabilityPolicy.VOLATILE,
        lifespan: Duration = DURATION_UNSPECIFIED,
        deadline: Duration = DURATION_UNSPECIFIED,
        liveliness: LivelinessPolicy | int = LivelinessPolicy.SYSTEM_DEFAULT,
        liveliness_lease_duration: Duration = DURATION_UNSPECIFIED,
        avoid_ros_namespace_conventions: bool = False,
    ) -> None:
        if history is None:
            if depth is None:
                raise InvalidQoSProfileException("History and/or depth settings are required.")
            history = HistoryPolicy.KEEP_LAST
        history = HistoryPolicy(history)
        if history == HistoryPolicy.KEEP_LAST and depth is None:
            raise InvalidQoSProfileException("History set to KEEP_LAST without a depth setting.")
        self._history = history
        self.depth = 0 if depth is None else depth
        self.reliability = reliability
        self.durability = durability
        self.lifespan = lifespan
        self.deadline = deadline
        self.liveliness = liveliness
        self.liveliness_lease_duration = liveliness_lease_duration
        self.avoid_ros_namespace_conventions = avoid_ros_namespace_conventions

    # -- fields (setters accept rmw's numbers and check what rclpy checks) -----------------
    @property
    def history(self) -> HistoryPolicy:
        """Keep the last `depth` samples, or all of them."""
        return self._history

    @history.setter
    def history(self, value: HistoryPolicy | int) -> None:
        """Set from the enum or its number."""
        self._history = HistoryPolicy(value)

    @property
    def depth(self) -> int:
        """How many samples KEEP_LAST keeps."""
        return self._depth

    @depth.setter
    def depth(self, value: int) -> None:
        """A non-negative int (0 with KEEP_LAST warns, as rclpy does)."""
        if isinstance(value, bool) or not isinstance(value, int):
            raise TypeError(f"QoS depth must be an int, not {type(value).__name__}")
        if value < 0:
            raise InvalidQoSProfileException(
                f"history depth must be greater than or equal to zero: {value}"
            )
        if self._history == HistoryPolicy.KEEP_LAST and value == 0:
            warnings.warn(
                "A zero depth with KEEP_LAST doesn't make sense; no data could be stored. "
                "This will be interpreted as SYSTEM_DEFAULT",
                UserWarning,
                stacklevel=2,
            )
        self._depth = value

    @property
    def reliability(self) -> ReliabilityPolicy:
        """Whether delivery is retried or may drop."""
        return self._reliability

    @reliability.setter
    def reliability(self, value: ReliabilityPolicy | int) -> None:
        """Set from the enum or its number."""
        self._reliability = ReliabilityPolicy(value)

    @property
    def durability(self) -> DurabilityPolicy:
        """Whether late joiners get the last samples."""
        return self._durability

    @durability.setter
    def durability(self, value: DurabilityPolicy | int) -> None:
        """Set from the enum or its number."""
        self._durability = DurabilityPolicy(value)

    @property
    def liveliness(self) -> LivelinessPolicy:
        """How a publisher shows it is alive."""
        return self._liveliness

    @liveliness.setter
    def liveliness(self, value: LivelinessPolicy | int) -> None:
        """Set from the enum or its number."""
        self._liveliness = LivelinessPolicy(value)

    @property
    def lifespan(self) -> Duration:
        """How long a sample stays valid (0: unspecified)."""
        return self._lifespan

    @lifespan.setter
    def lifespan(self, value: Duration) -> None:
        """A Duration."""
        self._lifespan = _duration("lifespan", value)

    @property
    def deadline(self) -> Duration:
        """The longest expected gap between samples (0: unspecified)."""
        return self._deadline

    @deadline.setter
    def deadline(self, value: Duration) -> None:
        """A Duration."""
        self._deadline = _duration("deadline", value)

    @property
    def liveliness_lease_duration(self) -> Duration:
        """How long a publisher may stay silent and still be alive."""
        return self._liveliness_lease_duration

    @liveliness_lease_duration.setter
    def liveliness_lease_duration(self, value: Duration) -> None:
        """A Duration."""
        self._liveliness_lease_duration = _duration("liveliness_lease_duration", value)

    @property
    def avoid_ros_namespace_conventions(self) -> bool:
        """Whether names skip ROS's namespace mangling."""
        return self._avoid_ros_namespace_conventions

    @avoid_ros_namespace_conventions.setter
    def avoid_ros_namespace_conventions(self, value: bool) -> None:
        """Set as a bool."""
        self._avoid_ros_namespace_conventions = bool(value)

    # -- value semantics --------------------------------------------------------------------
    def to_dict(self) -> dict[str, object]:
        """The profile as the keyword arguments that rebuild it."""
        return {f: getattr(self, f) for f in _FIELDS}

    def get_c_qos_profile(self) -> _RmwProfile:
        """The profile as rmw holds it (rclpy's accessor; here a plain record)."""
        return _RmwProfile(self.to_dict())

    def replace(self, **changes: object) -> QoSProfile:
        """A copy with some fields changed."""
        fields = self.to_dict()
        fields.update(changes)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", UserWarning)  # the original was accepted already
            return QoSProfile(**fields)  # type: ignore[arg-type]

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, QoSProfile):
            return NotImplemented
        return all(getattr(self, f) == getattr(other, f) for f in _FIELDS)

    __hash__ = None  # type: ignore[assignment]  # mutable, as rclpy's profiles are

    def __repr__(self) -> str:
        fields = ", ".join(f"{f}={getattr(self, f)!r}" for f in _FIELDS)
        return f"QoSProfile({fields})"

    @property
    def is_transient_local(self) -> bool:
        """Whether late subscribers get the last samples."""
        return self.durability == DurabilityPolicy.TRANSIENT_LOCAL


class _RmwProfile:
    """What :meth:`QoSProfile.get_c_qos_profile` gives: the fields, and `to_dict()`."""

    def __init__(self, fields: dict[str, object]) -> None:
        self._fields = fields

    def to_dict(self) -> dict[str, object]:
        return dict(self._fields)


def _duration(name: str, value: Duration) -> Duration:
    if not isinstance(value, Duration):
        raise TypeError(f"QoS {name.replace('_', ' ')} must be a Duration")
    if value.nanoseconds < 0:
        raise InvalidQoSProfileException(f"QoS {name.replace('_', ' ')} must not be negative")
    return value


# rclpy's older spellings of the policy enums
QoSReliabilityPolicy = ReliabilityPolicy
QoSDurabilityPolicy = DurabilityPolicy
QoSHistoryPolicy = HistoryPolicy
QoSLivelinessPolicy = LivelinessPolicy


_R, _D, _H, _L = ReliabilityPolicy, DurabilityPolicy, HistoryPolicy, LivelinessPolicy

qos_profile_default = QoSProfile(depth=10)
qos_profile_sensor_data = QoSProfile(reliability=_R.BEST_EFFORT, depth=5)
qos_profile_system_default = QoSProfile(
    reliability=_R.SYSTEM_DEFAULT,
    durability=_D.SYSTEM_DEFAULT,
    history=_H.SYSTEM_DEFAULT,
    depth=0,
)
qos_profile_services_default = QoSProfile(depth=10)
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
    return profile.replace(**changes)


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
    depth=10, reliability=ReliabilityPolicy.BEST_EFFORT, durability=DurabilityPolicy.VOLATILE
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


def zenoh_check_compatible(publisher: QoSProfile, subscription: QoSProfile) -> Compatibility:
    """What rmw_zenoh's own compatibility check says of the pair (what rclpy's
    ``qos_check_compatible`` returns on rmw_zenoh, and what its graph cache counts by).

    Zenoh delivers between any two QoS profiles, so no pair is incompatible; the one warning
    is a transient-local publisher with a volatile subscription, which misses the history.
    """
    if publisher.durability == _D.TRANSIENT_LOCAL and subscription.durability == _D.VOLATILE:
        return Compatibility(
            True,
            "WARNING: Publisher's durability is TRANSIENT_LOCAL, but subscription's is VOLATILE;",
        )
    return Compatibility(True, "")


def incompatible_policy(publisher: QoSProfile, subscription: QoSProfile) -> QoSPolicyKind | None:
    """The last policy (in rmw's order of checks) that makes the pair incompatible, or None:
    what QoS-incompatibility events report."""
    found = None
    for policy, error in _policy_errors(publisher, subscription):
        if error:
            found = policy
    return found


def _policy_errors(pub: QoSProfile, sub: QoSProfile) -> list[tuple[QoSPolicyKind, bool]]:
    pl, sl = pub.liveliness_lease_duration, sub.liveliness_lease_duration
    return [
        (
            QoSPolicyKind.RELIABILITY,
            pub.reliability == _R.BEST_EFFORT and sub.reliability == _R.RELIABLE,
        ),
        (
            QoSPolicyKind.DURABILITY,
            pub.durability == _D.VOLATILE and sub.durability == _D.TRANSIENT_LOCAL,
        ),
        (
            QoSPolicyKind.DEADLINE,
            not _no_duration(sub.deadline)
            and (_no_duration(pub.deadline) or sub.deadline < pub.deadline),
        ),
        (
            QoSPolicyKind.LIVELINESS,
            pub.liveliness == _L.AUTOMATIC and sub.liveliness == _L.MANUAL_BY_TOPIC,
        ),
        (
            QoSPolicyKind.LIVELINESS_LEASE_DURATION,
            not _no_duration(sl) and (_no_duration(pl) or sl < pl),
        ),
    ]


class QoSCompatibility(enum.IntEnum):
    """rclpy's verdict on a publisher/subscription pair."""

    OK = 0
    WARNING = 1
    ERROR = 2


def qos_check_compatible(
    publisher_qos: QoSProfile, subscription_qos: QoSProfile
) -> tuple[QoSCompatibility, str]:
    """rclpy's verdict on rmw_zenoh (:func:`zenoh_check_compatible`): (OK/WARNING/ERROR,
    reason); :func:`check_compatible` has DDS's."""
    compatible, reason = zenoh_check_compatible(publisher_qos, subscription_qos)
    if not compatible:
        return QoSCompatibility.ERROR, reason
    return (QoSCompatibility.WARNING if reason else QoSCompatibility.OK), reason


class QoSPolicyKind(enum.IntEnum):
    """Which policy an event or an override is about (rmw_qos_policy_kind_t)."""

    INVALID = 1 << 0
    DURABILITY = 1 << 1
    DEADLINE = 1 << 2
    LIVELINESS = 1 << 3
    RELIABILITY = 1 << 4
    HISTORY = 1 << 5
    LIFESPAN = 1 << 6
    DEPTH = 1 << 7
    LIVELINESS_LEASE_DURATION = 1 << 8
    AVOID_ROS_NAMESPACE_CONVENTIONS = 1 << 9


def qos_policy_name_from_kind(policy_kind: QoSPolicyKind | int) -> str:
    """'RELIABILITY_QOS_POLICY' and so on, as rmw names a policy kind."""
    return f"{QoSPolicyKind(policy_kind).name}_QOS_POLICY"


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
