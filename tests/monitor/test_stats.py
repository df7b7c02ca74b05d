"""The statistics behind hz/bw/delay and echo's lost-message report, without a network."""

from __future__ import annotations

import math
import statistics

from ros2lite.monitor.stats import (
    BandwidthStats,
    DelayStats,
    LostMessageCounter,
    RateStats,
    summarize,
)
from ros2lite.transport.attachment import encode_attachment

MS = 1_000_000


def test_summary_is_population_statistics() -> None:
    values = [10 * MS, 12 * MS, 9 * MS, 13 * MS]
    s = summarize(values)
    assert (s.min, s.max, s.count) == (9 * MS, 13 * MS, 4)
    assert s.mean == statistics.fmean(values)
    assert math.isclose(s.std_dev, statistics.pstdev(values))
    assert math.isclose(s.rate, 1e9 / statistics.fmean(values))


def test_rate_from_gaps_in_a_sliding_window() -> None:
    stats = RateStats(window=3)
    assert stats.summary() is None
    for t in (1000 * MS, 1010 * MS, 1030 * MS, 1060 * MS, 1100 * MS):
        assert stats.add(t) is False
    s = stats.summary()
    assert s is not None
    assert (s.count, s.min, s.max) == (3, 20 * MS, 40 * MS)  # oldest gap (10 ms) fell out
    assert math.isclose(s.rate, 1e9 / (30 * MS))
    assert stats.summary() is None  # nothing new since
    stats.add(1150 * MS)
    assert stats.summary() is not None


def test_rate_restarts_when_time_goes_back_or_resets() -> None:
    stats = RateStats()
    stats.add(5000 * MS)
    stats.add(5100 * MS)
    stats.add(4000 * MS)  # clock jumped back: start over, no gap recorded
    assert stats.peek() is None
    stats.add(4100 * MS)
    assert stats.add(0) is True  # sim time reset reports that it cleared something
    assert stats.add(0) is False
    assert stats.peek() is None


def test_bandwidth_over_time_since_oldest_sample() -> None:
    stats = BandwidthStats(window=3)
    stats.add(1000 * MS, 100)
    assert stats.summary(2000 * MS) is None  # needs two samples
    for t, size in ((1100 * MS, 200), (1200 * MS, 300), (1300 * MS, 400)):
        stats.add(t, size)
    s = stats.summary(2100 * MS)
    assert s is not None
    assert (s.count, s.min, s.max, s.mean) == (3, 200, 400, 300)
    assert math.isclose(s.bytes_per_second, 900 / 1.0)
    assert stats.summary(1000 * MS) is None  # clock behind the window: reset
    assert stats.summary(3000 * MS) is None


def test_delay_ignores_the_first_sample_like_ros2cli() -> None:
    stats = DelayStats(window=2)
    stats.add(1000 * MS, 900 * MS)
    assert stats.empty and stats.summary() is None
    stats.add(2000 * MS, 1800 * MS)
    stats.add(3000 * MS, 2700 * MS)
    stats.add(4000 * MS, 3600 * MS)
    s = stats.summary()
    assert s is not None and (s.count, s.min, s.max) == (2, 300 * MS, 400 * MS)
    assert stats.summary() is None


def test_lost_messages_per_publisher() -> None:
    lost = LostMessageCounter()
    a, b = bytes(range(16)), bytes(range(1, 17))
    for seq in (1, 2, 5):
        lost.observe_attachment(encode_attachment(seq, 0, a))
    for seq in (7, 8, 9):
        lost.observe_attachment(encode_attachment(seq, 0, b))  # first sight of b: no loss
    lost.observe_attachment(encode_attachment(6, 0, a))
    lost.observe_attachment(encode_attachment(12, 0, b))
    assert lost.drain() == [(2, 2), (2, 4)]
    assert lost.drain() == []
    lost.observe_attachment(b'not an attachment')  # ignored, not fatal
