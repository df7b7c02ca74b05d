"""`topic delay`: age of messages from their header stamp."""

from __future__ import annotations

import re
import time
from collections.abc import Callable
from typing import Any

from ros2lite.interfaces import get_interface

from ...conftest import wait_until
from ..conftest import Result
from .conftest import Watch

PointStamped = get_interface('geometry_msgs/msg/PointStamped')
Time = get_interface('builtin_interfaces/msg/Time')
BLOCK = re.compile(
    r'average delay: (-?\d+\.\d{3})\n\tmin: (-?\d+\.\d{3})s max: (-?\d+\.\d{3})s '
    r'std dev: (\d+\.\d{5})s window: (\d+)\n'
)


def stamped(age: float) -> Callable[[int], Any]:
    def make(_i: int) -> Any:
        ns = time.time_ns() - int(age * 1e9)
        msg = PointStamped()
        msg.header.stamp = Time(sec=ns // 10**9, nanosec=ns % 10**9)
        return msg

    return make


def test_delay_of_stamped_messages(processes: Any, talker: Any, topic: str) -> None:
    source = talker(topic, 'geometry_msgs/msg/PointStamped', stamped(0.25), rate=50)
    delay = Watch(processes.cli('topic', 'delay', topic))
    wait_until(lambda: len(BLOCK.findall(delay.text)) >= 2, timeout=15)
    source.stop()
    wait_until(lambda: delay.text.endswith('no new messages\n'), timeout=5)
    delay.interrupt()
    blocks = BLOCK.findall(delay.text)
    assert BLOCK.sub('', delay.text).replace('no new messages\n', '') == ''
    for mean, low, high, _std, window in blocks:
        # stamps are 0.25 s old when sent; what comes on top is transport and scheduling
        # latency, which a loaded machine can stretch to tens of milliseconds, so the upper
        # bound only rules out a wrong computation (seconds vs nanoseconds, a sign)
        assert 0.25 <= float(low) <= float(mean) <= float(high) < 1.25, delay.text
        assert int(window) >= 30


def test_needs_a_header(run: Callable[..., Result], talker: Any, topic: str) -> None:
    string = get_interface('std_msgs/msg/String')
    talker(topic, 'std_msgs/msg/String', lambda i: string(data='no header'))
    result = run('topic', 'delay', topic)
    assert (result.code, result.err) == (1, 'msg does not have header\n')
