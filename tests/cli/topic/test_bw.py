"""`topic bw`: sizes of raw samples, the unit choice and the report format."""

from __future__ import annotations

import re
from typing import Any

from ros2lite.cli.topic.bw import bw_line
from ros2lite.interfaces import get_interface, serialize
from ros2lite.monitor.stats import BandwidthSummary

from ...conftest import wait_until
from .conftest import Watch

String = get_interface('std_msgs/msg/String')
BLOCK = re.compile(
    r'(\d+\.\d{2}) KB/s from (\d+) messages\n'
    r'\tMessage size mean: (\S+) KB min: (\S+) KB max: (\S+) KB\n'
)


def test_bandwidth_of_a_steady_publisher(processes: Any, talker: Any, topic: str) -> None:
    msg = String(data='x' * 96)
    size = len(serialize(msg))  # what travels: CDR with its 4-byte header
    talker(topic, 'std_msgs/msg/String', lambda i: msg, rate=50)
    bw = Watch(processes.cli('topic', 'bw', topic))
    wait_until(lambda: len(BLOCK.findall(bw.text)) >= 2, timeout=15)
    bw.interrupt()
    head = f'Subscribed to [{topic}]\n'
    assert bw.text.startswith(head)
    assert BLOCK.sub('', bw.text[len(head) :]) == ''
    expected_size = f'{size / 1000:.2f}'
    for rate, count, mean, low, high in BLOCK.findall(bw.text):
        assert (mean, low, high) == (expected_size,) * 3
        # n samples over (now - oldest sample) spans at least n - 1 periods, so the rate is at
        # most n / (n - 1) of the true 50 * size per second, plus some timer jitter
        n = int(count)
        assert 2 <= n <= 100
        true_rate = 50 * size / 1000
        assert 0.85 * true_rate <= float(rate) <= n / (n - 1) * true_rate * 1.03, (rate, n)


def test_window_limits_the_message_count(processes: Any, talker: Any, topic: str) -> None:
    talker(topic, 'std_msgs/msg/String', lambda i: String(data='y' * 1000), rate=50)
    bw = Watch(processes.cli('topic', 'bw', topic, '-w', '5'))
    wait_until(lambda: len(BLOCK.findall(bw.text)) >= 1, timeout=15)
    bw.interrupt()
    assert {count for _, count, *_ in BLOCK.findall(bw.text)} == {'5'}


def test_unit_follows_the_rate() -> None:
    assert bw_line(BandwidthSummary(999.4, 3, 33.3, 30, 40)) == (
        '999 B/s from 3 messages\n\tMessage size mean: 33 B min: 30 B max: 40 B'
    )
    assert bw_line(BandwidthSummary(1234.0, 100, 52.0, 50, 54)) == (
        '1.23 KB/s from 100 messages\n\tMessage size mean: 0.05 KB min: 0.05 KB max: 0.05 KB'
    )
    assert bw_line(BandwidthSummary(2.5e6, 10, 250000.0, 250000, 250000)) == (
        '2.50 MB/s from 10 messages\n\tMessage size mean: 0.25 MB min: 0.25 MB max: 0.25 MB'
    )
