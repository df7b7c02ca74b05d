"""Statistics behind `topic hz`, `topic bw`, `topic delay` and echo's lost-message report.

They live in the library (not the CLI) so scripts and benchmarks can measure topics the same
way the command line does. Every class takes timestamps from its caller, in nanoseconds, so
the caller decides the clock (ROS time, wall time, or a sample's arrival time) and the maths
can be tested without a network. Samples are fed from Zenoh or executor threads while a
printer reads the results, hence the locks.
"""

from __future__ import annotations

import math
import threading
from collections import deque
from collections.abc import Sequence
from dataclasses import dataclass

from ros2lite.transport.attachment import unpack_attachment

__all__ = [
    'BandwidthStats',
    'BandwidthSummary',
    'DelayStats',
    'IntervalSummary',
    'LostMessageCounter',
    'RateStats',
    'summarize',
]

_NS = 1_000_000_000


@dataclass(frozen=True)
class IntervalSummary:
    """Mean, extremes and population standard deviation of a window of durations (ns)."""

    mean: float
    min: int
    max: int
    std_dev: float
    count: int

    @property
    def rate(self) -> float:
        """Events per second when the durations are gaps between events (0 if undefined)."""
        return _NS / self.mean if self.mean > 0 else 0.0


def summarize(values: Sequence[int]) -> IntervalSummary:
    """Summary of a non-empty sequence of integer nanosecond values."""
    n = len(values)
    total = sum(values)
    mean = total / n
    # population variance, as ros2cli computes it; fsum keeps 10^4 squares exact enough
    var = math.fsum((v - mean) ** 2 for v in values) / n
    return IntervalSummary(mean, min(values), max(values), math.sqrt(var), n)


class RateStats:
    """`topic hz` for one topic: gaps between consecutive samples in a sliding window.

    The rate is 1 / mean gap, i.e. (n gaps) / (time spanned by the window), so it is exact
    whenever the arrival timestamps are, however late a consumer reads them.
    """

    def __init__(self, window: int = 10000) -> None:
        if window < 1:
            raise ValueError('window must be a positive number of messages')
        self.window = window
        self._lock = threading.Lock()
        self._gaps: deque[int] = deque(maxlen=window)
        self._first = -1  # time of the sample that started this run of gaps
        self._last = 0  # time of the newest sample
        self._reported = 0  # newest sample time when a summary was last handed out

    def add(self, now_ns: int) -> bool:
        """Record one sample seen at `now_ns`; True when a clock reset cleared the window.

        A clock reading 0 (sim time before /clock) or a clock that went backwards starts over,
        as ros2cli does.
        """
        with self._lock:
            if now_ns == 0:
                had = bool(self._gaps)
                self._gaps.clear()
                return had
            if self._first < 0 or self._first > now_ns:
                self._first = self._last = now_ns
                self._gaps.clear()
                return False
            self._gaps.append(now_ns - self._last)
            self._last = now_ns
            return False

    def summary(self) -> IntervalSummary | None:
        """The window's statistics if a sample arrived since the last call, else None."""
        with self._lock:
            if not self._gaps or self._last == self._reported:
                return None
            self._reported = self._last
            gaps = list(self._gaps)
        return summarize(gaps)

    def peek(self) -> IntervalSummary | None:
        """The window's statistics without marking them reported."""
        with self._lock:
            gaps = list(self._gaps)
        return summarize(gaps) if gaps else None


@dataclass(frozen=True)
class BandwidthSummary:
    """`topic bw`'s figures over its window."""

    bytes_per_second: float
    count: int
    mean: float
    min: int
    max: int


class BandwidthStats:
    """`topic bw`: serialized sizes of the last `window` samples and when they arrived."""

    def __init__(self, window: int = 100) -> None:
        if window < 1:
            raise ValueError('window must be a positive number of messages')
        self._lock = threading.Lock()
        self._samples: deque[tuple[int, int]] = deque(maxlen=window)

    def add(self, now_ns: int, size: int) -> None:
        """Count one message of `size` bytes that arrived at `now_ns`."""
        with self._lock:
            self._samples.append((now_ns, size))

    def summary(self, now_ns: int) -> BandwidthSummary | None:
        """Bytes/s over (now - oldest sample in the window); None with fewer than 2 samples.

        A clock that is not past the oldest sample (time went backwards) clears the window.
        """
        with self._lock:
            if len(self._samples) < 2:
                return None
            first = self._samples[0][0]
            if now_ns <= first:
                self._samples.clear()
                return None
            sizes = [s for _, s in self._samples]
        total = sum(sizes)
        n = len(sizes)
        return BandwidthSummary(
            total * _NS / (now_ns - first), n, total / n, min(sizes), max(sizes)
        )


class DelayStats:
    """`topic delay`: receive time minus header stamp, in a sliding window.

    Like ros2cli, the first sample only starts the clock and adds no delay.
    """

    def __init__(self, window: int = 10000) -> None:
        self._lock = threading.Lock()
        self.window = window
        self._delays: deque[int] = deque()
        self._first = -1
        self._last = 0
        self._reported = 0

    def add(self, now_ns: int, stamp_ns: int) -> bool:
        """Record one sample; True when a clock reset cleared the window."""
        with self._lock:
            if now_ns == 0:
                had = bool(self._delays)
                self._delays.clear()
                return had
            if self._first < 0 or self._first > now_ns:
                self._first = self._last = now_ns
                self._delays.clear()
            else:
                self._delays.append(now_ns - stamp_ns)
                self._last = now_ns
            while len(self._delays) > self.window:
                self._delays.popleft()
            return False

    @property
    def empty(self) -> bool:
        """Whether no delay has been measured yet."""
        with self._lock:
            return not self._delays

    def summary(self) -> IntervalSummary | None:
        """Statistics if a sample arrived since the last call, else None."""
        with self._lock:
            if self._last == self._reported or not self._delays:
                return None
            self._reported = self._last
            delays = list(self._delays)
        return summarize(delays)


class LostMessageCounter:
    """Sequence-number gaps per publisher GID, as rmw_zenoh reports 'message lost' events.

    Feed it every attachment on arrival; `drain()` returns the (count change, total) events
    seen since the previous call.
    """

    def __init__(self) -> None:
        self._lock = threading.Lock()
        self._last: dict[bytes, int] = {}
        self.total = 0
        self._events: list[tuple[int, int]] = []

    def observe(self, sequence_number: int, gid: bytes) -> None:
        """Note a sample's sequence number; gaps per publisher count as lost."""
        with self._lock:
            last = self._last.get(gid)
            self._last[gid] = sequence_number
            if last is None:
                return
            jump = abs(sequence_number - last)
            if jump > 1:
                self.total += jump - 1
                self._events.append((jump - 1, self.total))

    def observe_attachment(self, attachment: bytes) -> None:
        """Count the sample whose rmw_zenoh attachment this is (unreadable ones are not)."""
        fields = unpack_attachment(attachment)
        if fields is not None:
            self.observe(fields[0], fields[2])

    def drain(self) -> list[tuple[int, int]]:
        """(change, total) of each loss noticed since the last call."""
        with self._lock:
            events, self._events = self._events, []
        return events
