"""QoS profiles, presets, rclpy's policy names, compatibility and BEST_AVAILABLE rules."""

from __future__ import annotations

import pytest

from ros2lite import qos as q
from ros2lite.qos import (
    DURATION_BEST_AVAILABLE,
    DURATION_INFINITE,
    DurabilityPolicy,
    Duration,
    HistoryPolicy,
    LivelinessPolicy,
    QoSProfile,
    ReliabilityPolicy,
    check_compatible,
    preset,
    resolve_best_available,
)
from ros2lite.transport.qos import decode_qos


def test_presets_and_short_keys() -> None:
    assert preset("sensor_data") is q.qos_profile_sensor_data
    assert preset("qos_profile_sensor_data") is q.qos_profile_sensor_data
    assert preset("rosout_default").lifespan == Duration(seconds=10)
    assert preset("parameters").depth == preset("parameter_events").depth == 1000
    assert preset("action_status_default").durability == DurabilityPolicy.TRANSIENT_LOCAL
    assert preset("system_default").reliability == ReliabilityPolicy.SYSTEM_DEFAULT
    assert QoSProfile(depth=10) == QoSProfile(
        reliability=ReliabilityPolicy.RELIABLE,
        durability=DurabilityPolicy.VOLATILE,
        history=HistoryPolicy.KEEP_LAST,
        depth=10,
    )
    with pytest.raises(ValueError, match="sensor_data"):
        preset("nope")
    assert ReliabilityPolicy.from_short_key("best_effort") is ReliabilityPolicy.BEST_EFFORT
    assert DurabilityPolicy.from_short_key("transient_local") is DurabilityPolicy.TRANSIENT_LOCAL
    assert HistoryPolicy.from_short_key("KEEP_ALL") is HistoryPolicy.KEEP_ALL
    assert ReliabilityPolicy.RELIABLE.short_key == "reliable"
    assert "system_default" in ReliabilityPolicy.short_keys()
    with pytest.raises(ValueError, match="reliable, best_effort"):
        ReliabilityPolicy.from_short_key("sometimes")


def test_profile_accepts_ints_and_checks_depth() -> None:
    assert QoSProfile(depth=10, reliability=2).reliability is ReliabilityPolicy.BEST_EFFORT  # type: ignore[arg-type]
    assert QoSProfile(depth=10).replace(depth=3).depth == 3
    with pytest.raises(ValueError):
        QoSProfile(depth=-1)


def test_duration_helpers() -> None:
    assert Duration.from_seconds(10) == Duration(seconds=10)
    assert Duration.from_nanoseconds(1_500_000_000) == Duration(seconds=1, nanoseconds=500000000)
    assert str(DURATION_INFINITE) == "Infinite"
    assert str(Duration(seconds=1, nanoseconds=5)) == "1000000005 nanoseconds"
    assert Duration(seconds=1) < Duration(seconds=1, nanoseconds=1) < Duration(seconds=2)


R, D, L = ReliabilityPolicy, DurabilityPolicy, LivelinessPolicy


@pytest.mark.parametrize(
    ("pub", "sub", "ok", "fragment"),
    [
        (
            QoSProfile(depth=10, reliability=R.BEST_EFFORT),
            QoSProfile(depth=10),
            False,
            "Best effort publisher",
        ),
        (QoSProfile(depth=10), QoSProfile(depth=10, reliability=R.BEST_EFFORT), True, ""),
        (
            QoSProfile(depth=10),
            QoSProfile(depth=10, durability=D.TRANSIENT_LOCAL),
            False,
            "Volatile publisher",
        ),
        (QoSProfile(depth=10, durability=D.TRANSIENT_LOCAL), QoSProfile(depth=10), True, ""),
        (
            QoSProfile(depth=10),
            QoSProfile(depth=10, deadline=Duration(seconds=1)),
            False,
            "publisher does not",
        ),
        (
            QoSProfile(depth=10, deadline=Duration(seconds=2)),
            QoSProfile(depth=10, deadline=Duration(seconds=1)),
            False,
            "deadline is less",
        ),
        (
            QoSProfile(depth=10, deadline=Duration(seconds=1)),
            QoSProfile(depth=10, deadline=Duration(seconds=2)),
            True,
            "",
        ),
        (
            QoSProfile(depth=10, liveliness=L.AUTOMATIC),
            QoSProfile(depth=10, liveliness=L.MANUAL_BY_TOPIC),
            False,
            "manual by topic",
        ),
        (
            QoSProfile(depth=10),
            QoSProfile(depth=10, liveliness_lease_duration=Duration(seconds=1)),
            False,
            "lease duration, but publisher does not",
        ),
        (
            QoSProfile(depth=10, liveliness_lease_duration=Duration(seconds=3)),
            QoSProfile(depth=10, liveliness_lease_duration=Duration(seconds=1)),
            False,
            "less than publisher",
        ),
        # Tokens carry "infinite" where users write "unspecified": both mean no deadline.
        (decode_qos("::,10:,:,:,,"), QoSProfile(depth=10), True, ""),
        (QoSProfile(depth=10), decode_qos("::,10:,:,:,,"), True, ""),
        (q.qos_profile_system_default, q.qos_profile_system_default, True, "WARNING"),
    ],
)
def test_compatibility(pub: QoSProfile, sub: QoSProfile, ok: bool, fragment: str) -> None:
    compatible, reason = check_compatible(pub, sub)
    assert compatible is ok
    assert fragment in reason
    if not fragment:
        assert reason == "" or reason.startswith("WARNING")


def test_resolve_best_available() -> None:
    ba = q.qos_profile_best_available
    pub = resolve_best_available(ba, [], for_publisher=True)
    assert (pub.reliability, pub.durability, pub.liveliness) == (
        R.RELIABLE,
        D.TRANSIENT_LOCAL,
        L.AUTOMATIC,
    )
    assert pub.deadline.is_unspecified
    pubs = [
        QoSProfile(depth=10, reliability=R.BEST_EFFORT, deadline=Duration(seconds=2)),
        QoSProfile(depth=10, durability=D.TRANSIENT_LOCAL, deadline=Duration(seconds=5)),
    ]
    sub = resolve_best_available(ba, pubs, for_publisher=False)
    assert (sub.reliability, sub.durability) == (R.BEST_EFFORT, D.VOLATILE)
    assert sub.deadline == Duration(seconds=5)
    assert sub.liveliness_lease_duration.is_unspecified
    tl = resolve_best_available(ba, [q.qos_profile_rosout_default], for_publisher=False)
    assert (tl.reliability, tl.durability) == (R.RELIABLE, D.TRANSIENT_LOCAL)
    assert ba.deadline == DURATION_BEST_AVAILABLE


def test_rclpy_policy_aliases() -> None:
    assert q.QoSReliabilityPolicy is ReliabilityPolicy
    assert q.QoSHistoryPolicy.KEEP_ALL is HistoryPolicy.KEEP_ALL
    assert q.QoSDurabilityPolicy is DurabilityPolicy
    assert q.QoSLivelinessPolicy is LivelinessPolicy


def test_rclpy_profile_rules() -> None:
    from ros2lite.qos import InvalidQoSProfileException

    with pytest.raises(InvalidQoSProfileException):
        QoSProfile()
    with pytest.raises(InvalidQoSProfileException):
        QoSProfile(history=HistoryPolicy.KEEP_LAST)
    assert QoSProfile(history=HistoryPolicy.KEEP_ALL).depth == 0
    profile = QoSProfile(depth=1)
    profile.reliability = 2  # type: ignore[assignment]  # rmw's numbers are accepted
    assert profile.reliability is ReliabilityPolicy.BEST_EFFORT
    with pytest.warns(UserWarning, match="zero depth with KEEP_LAST"):
        profile.depth = 0
    profile.depth = 3
    with pytest.raises(ValueError, match="greater than or equal to zero"):
        QoSProfile(depth=-1)
    copy = QoSProfile(**profile.get_c_qos_profile().to_dict())  # type: ignore[arg-type]
    assert copy == profile and copy is not profile
    assert HistoryPolicy.get_from_short_key("KEEP_all") == HistoryPolicy.KEEP_ALL.value


def test_rclpy_compatibility_verdicts() -> None:
    from ros2lite.qos import (
        QoSCompatibility,
        QoSPolicyKind,
        incompatible_policy,
        qos_check_compatible,
        qos_profile_system_default,
    )

    reliable = QoSProfile(depth=1, liveliness=L.AUTOMATIC)
    best_effort = QoSProfile(depth=1, reliability=R.BEST_EFFORT)
    # rclpy on rmw_zenoh: its own rule, no pair is an error
    assert qos_check_compatible(reliable, reliable) == (QoSCompatibility.OK, "")
    assert qos_check_compatible(best_effort, reliable) == (QoSCompatibility.OK, "")
    assert qos_check_compatible(qos_profile_system_default, reliable)[0] == QoSCompatibility.OK
    latched = QoSProfile(depth=1, durability=D.TRANSIENT_LOCAL)
    verdict, reason = qos_check_compatible(latched, reliable)
    assert verdict == QoSCompatibility.WARNING and "TRANSIENT_LOCAL" in reason
    assert incompatible_policy(best_effort, reliable) == QoSPolicyKind.RELIABILITY
    transient = QoSProfile(depth=1, durability=D.TRANSIENT_LOCAL)
    assert incompatible_policy(best_effort, transient) == QoSPolicyKind.DURABILITY  # the last
    assert incompatible_policy(reliable, best_effort) is None


def test_qos_matching_publishers() -> None:
    rel = QoSProfile(depth=10)
    be = QoSProfile(depth=10, reliability=ReliabilityPolicy.BEST_EFFORT)
    tl = QoSProfile(depth=10, durability=DurabilityPolicy.TRANSIENT_LOCAL)
    base = q.qos_profile_sensor_data
    assert q.match_publishers_qos(base, []).profile == base
    all_rel = q.match_publishers_qos(base, [rel, tl])
    assert all_rel.profile.reliability == ReliabilityPolicy.RELIABLE
    assert all_rel.profile.durability == DurabilityPolicy.VOLATILE
    assert (all_rel.reliability_fell_back, all_rel.durability_fell_back) == (False, True)
    mixed = q.match_publishers_qos(base, [rel, be])
    assert mixed.profile.reliability == ReliabilityPolicy.BEST_EFFORT
    assert (mixed.reliability_fell_back, mixed.durability_fell_back) == (True, False)
    latched = q.match_publishers_qos(base, [tl])
    assert latched.profile.durability == DurabilityPolicy.TRANSIENT_LOCAL
    assert latched.profile.depth == base.depth
    unknown = q.match_publishers_qos(base, [None])
    assert unknown.profile.reliability == ReliabilityPolicy.BEST_EFFORT
