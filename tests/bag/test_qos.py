"""The recorder's and the player's QoS adaptation (rosbag2's rules), and override files."""

from __future__ import annotations

import pytest

from ros2lite.bag.qos import (
    QoSOverrideError,
    parse_qos_overrides,
    playback_qos,
    read_qos_overrides,
    recording_qos,
)
from ros2lite.duration import Duration
from ros2lite.qos import DurabilityPolicy, HistoryPolicy, QoSProfile, ReliabilityPolicy

LATCHED = QoSProfile(durability=DurabilityPolicy.TRANSIENT_LOCAL, depth=20)
BEST_EFFORT = QoSProfile(reliability=ReliabilityPolicy.BEST_EFFORT, depth=5)
KEEP_ALL = QoSProfile(history=HistoryPolicy.KEEP_ALL)


def test_playback_offers_what_all_recorded_publishers_offered() -> None:
    assert playback_qos("/t", []) == QoSProfile(depth=10)
    q = playback_qos("/t", [LATCHED, LATCHED.replace(depth=3)])
    assert (q.durability, q.reliability, q.depth) == (
        DurabilityPolicy.TRANSIENT_LOCAL,
        ReliabilityPolicy.RELIABLE,
        20,
    )
    assert playback_qos("/t", [KEEP_ALL]).history == HistoryPolicy.KEEP_ALL
    # history does not decide compatibility: the same offer, but not all kept all
    assert playback_qos("/t", [KEEP_ALL, QoSProfile(depth=10)]).history == HistoryPolicy.KEEP_LAST


def test_playback_falls_back_to_the_default_offer_on_mixed_offers() -> None:
    warnings: list[str] = []
    q = playback_qos("/mixed", [LATCHED, BEST_EFFORT], warnings.append)
    assert q == QoSProfile(depth=10)  # reliable, volatile, keep last 10, as rosbag2 falls back
    assert len(warnings) == 1 and "'/mixed'" in warnings[0]
    deadline = QoSProfile(depth=10, deadline=Duration(seconds=1))
    assert playback_qos("/d", [deadline, QoSProfile(depth=10)], warnings.append) == QoSProfile(
        depth=10
    )


def test_recording_asks_for_what_every_publisher_offers() -> None:
    warnings: list[str] = []
    q = recording_qos("/t", [LATCHED, LATCHED], warnings.append)
    assert (q.reliability, q.durability, q.history, q.depth) == (
        ReliabilityPolicy.RELIABLE,
        DurabilityPolicy.TRANSIENT_LOCAL,
        HistoryPolicy.KEEP_ALL,
        20,
    )
    assert warnings == []
    q = recording_qos("/mixed", [LATCHED, BEST_EFFORT], warnings.append)
    assert (q.reliability, q.durability) == (
        ReliabilityPolicy.BEST_EFFORT,
        DurabilityPolicy.VOLATILE,
    )
    assert len(warnings) == 2 and all("'/mixed'" in w for w in warnings)
    assert recording_qos("/none", []).history == HistoryPolicy.KEEP_ALL


def test_override_files(tmp_path: object) -> None:
    from pathlib import Path

    assert isinstance(tmp_path, Path)
    path = tmp_path / "o.yaml"
    path.write_text("/a:\n  reliability: best_effort\n  depth: 3\n")
    assert read_qos_overrides(path)["/a"] == QoSProfile(
        reliability=ReliabilityPolicy.BEST_EFFORT, depth=3
    )
    with pytest.raises(QoSOverrideError, match="Unexpected key"):
        parse_qos_overrides("/a: {colour: red}")
    with pytest.raises(Exception, match="Cannot read"):
        read_qos_overrides(tmp_path / "missing.yaml")


@pytest.mark.parametrize('depth', ['100000000000000000000', '1.0e+20', '-1', 'true', '2.5'])
def test_an_override_depth_no_queue_holds_is_one_line(depth: str) -> None:
    """R5: a depth of 1e20 made `bag record` fail its queue set-up and record nothing while
    it kept running; the override file is refused before recording starts."""
    with pytest.raises(QoSOverrideError, match=r"QoS override depth of '/c' must be an integer"):
        parse_qos_overrides(f'/c:\n  depth: {depth}\n')


def test_a_large_but_sane_override_depth_is_kept() -> None:
    assert parse_qos_overrides('/c:\n  depth: 100000\n')['/c'].depth == 100000
