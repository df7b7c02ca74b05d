from __future__ import annotations

import pytest

from ros2lite import qos as q
from ros2lite.qos import (
    DURATION_INFINITE,
    DurabilityPolicy,
    Duration,
    HistoryPolicy,
    LivelinessPolicy,
    QoSProfile,
    ReliabilityPolicy,
)
from ros2lite.transport import qos as wire
from ros2lite.transport.qos import best_available_qos, decode_qos, encode_qos

# The worked values of the rmw_zenoh reference, §2.2.
WORKED = [
    (QoSProfile(depth=10), "::,10:,:,:,,"),  # rclcpp QoS(10), services
    (q.qos_profile_services_default, "::,10:,:,:,,"),
    (QoSProfile(depth=7), "::,7:,:,:,,"),  # the talker
    (q.qos_profile_sensor_data, "2::,5:,:,:,,"),  # best effort depth 5
    (q.qos_profile_rosout_default, ":1:,1000:,:10,0:,,"),
    (q.qos_profile_action_status_default, ":1:,1:,:,:,,"),
    (q.qos_profile_parameters, "::,1000:,:,:,,"),
    (q.qos_profile_parameter_events, "::,1000:,:,:,,"),
]


@pytest.mark.parametrize(("profile", "chunk"), WORKED)
def test_worked_values(profile: QoSProfile, chunk: str) -> None:
    assert encode_qos(profile) == chunk
    assert decode_qos(chunk) == best_available_qos(profile)


def test_rmw_zenoh_defaults_encode_empty() -> None:
    assert encode_qos(wire.ZENOH_DEFAULT_QOS) == "::,:,:,:,,"
    # SYSTEM_DEFAULT everywhere and depth 0 normalise to those defaults.
    assert encode_qos(q.qos_profile_system_default) == "::,:,:,:,,"
    assert decode_qos("::,:,:,:,,") == wire.ZENOH_DEFAULT_QOS


def test_best_available_normalisation() -> None:
    with pytest.warns(UserWarning, match="zero depth"):  # rclpy's warning for KEEP_LAST 0
        zero = QoSProfile(depth=0)
    norm = best_available_qos(zero)
    assert norm.depth == 42
    assert norm.deadline == norm.lifespan == norm.liveliness_lease_duration == DURATION_INFINITE
    assert norm.liveliness == LivelinessPolicy.AUTOMATIC
    # BEST_AVAILABLE is advertised unresolved, like rmw_zenoh does.
    assert (
        encode_qos(QoSProfile(depth=10, reliability=ReliabilityPolicy.BEST_AVAILABLE))
        == "4::,10:,:,:,,"
    )
    with pytest.raises(ValueError, match="UNKNOWN"):
        best_available_qos(q.qos_profile_unknown)


def test_explicit_values_round_trip() -> None:
    profile = QoSProfile(
        reliability=ReliabilityPolicy.BEST_EFFORT,
        durability=DurabilityPolicy.TRANSIENT_LOCAL,
        history=HistoryPolicy.KEEP_ALL,
        depth=3,
        deadline=Duration(seconds=1, nanoseconds=500),
        lifespan=Duration.from_seconds(2.5),
        liveliness=LivelinessPolicy.MANUAL_BY_TOPIC,
        liveliness_lease_duration=Duration(seconds=4),
    )
    chunk = encode_qos(profile)
    assert chunk == "2:1:2,3:1,500:2,500000000:3,4,0"
    assert decode_qos(chunk) == profile


def test_lenient_decode_of_old_default_durability() -> None:
    # Jazzy 0.2.0-0.2.2 peers wrote ':2:' for volatile and '::' for transient local.
    assert decode_qos(":2:,10:,:,:,,").durability == DurabilityPolicy.VOLATILE
    assert decode_qos("::,10:,:,:,,").durability == DurabilityPolicy.VOLATILE
    old_tl = decode_qos("::,10:,:,:,,", default_durability=DurabilityPolicy.TRANSIENT_LOCAL)
    assert old_tl.durability == DurabilityPolicy.TRANSIENT_LOCAL
    # Missing trailing fields take defaults.
    assert decode_qos("2::,5") == decode_qos("2::,5:,:,:,,")


@pytest.mark.parametrize(
    "chunk",
    ["", "abc", "x::,:,:,:,,", "::,ten:,:,:,,", "9::,:,:,:,,", "::,:,:,:,,:", "::,1,2:,:,:,,"],
)
def test_garbage_chunks_raise(chunk: str) -> None:
    with pytest.raises(ValueError, match="QoS chunk"):
        decode_qos(chunk)
