"""One frame's history: where the frame was, relative to which parent, over the cache length.

A moving frame keeps every transform of the last `cache_time` in packed arrays (stamps,
parents, and 7 doubles each), oldest first, so that a 1 kHz frame costs ~70 bytes a sample and
a lookup is one bisection; a static frame keeps one transform, valid at every time. The rules
(what is pruned when, what is extrapolation, which sample wins at equal stamps) are tf2's
TimeCache and StaticCache.
"""

from __future__ import annotations

import enum
from array import array
from bisect import bisect_left, bisect_right

from ros2lite.tf2.math import Quat, Vec, lerp, slerp

__all__ = ['CacheError', 'FrameCache', 'StaticCache', 'TimeCache', 'display_time', 'to_seconds']

_COMPACT_AT = 256  # dead entries at the front (and at least half) before a shift down


class CacheError(enum.IntEnum):
    """Why a cache had no answer at a time (tf2's TF2Error codes of the cache's making)."""

    NO_DATA = 1
    FORWARD = 2
    BACKWARD = 3


def display_time(ns: int) -> str:
    """A time point as tf2 writes it in messages: seconds with 6 decimals."""
    return f'{to_seconds(ns):.6f}'


def to_seconds(ns: int) -> float:
    """Seconds as tf2's durationToSec computes them (whole and fraction scaled apart)."""
    nsec = ns % 1_000_000_000 if ns >= 0 else -((-ns) % 1_000_000_000)
    return float((ns - nsec) // 1_000_000_000) + 1e-9 * nsec


Sample = tuple[int, Vec, Quat]
"""(parent id, translation, rotation) of a frame at one time."""


class TimeCache:
    """The recent history of a moving frame, pruned to `cache_ns` behind its newest sample."""

    __slots__ = ('_cache_ns', '_parents', '_stamps', '_start', '_values')

    def __init__(self, cache_ns: int) -> None:
        self._cache_ns = cache_ns
        self._stamps = array('q')
        self._parents = array('q')
        self._values = array('d')
        self._start = 0  # entries before this index are pruned, not yet shifted out

    def __len__(self) -> int:
        return len(self._stamps) - self._start

    def insert(self, stamp: int, parent: int, translation: Vec, rotation: Quat) -> bool:
        """Store a sample; False (and nothing stored) when it is older than the cache keeps.
        An exact repeat of a stored sample is not stored twice."""
        stamps = self._stamps
        if len(stamps) > self._start:
            latest = stamps[-1]
            if stamps[self._start] + self._cache_ns < latest:
                self._prune(latest)
            if stamp < latest - self._cache_ns:
                return False
            if stamp > latest:  # the usual case: the newest sample goes at the end
                stamps.append(stamp)
                self._parents.append(parent)
                self._values.extend(translation)
                self._values.extend(rotation)
                return True
        values = (*translation, *rotation)
        at = bisect_right(stamps, stamp, self._start)
        same = at - 1
        while same >= self._start and stamps[same] == stamp:
            stored = tuple(self._values[same * 7 : same * 7 + 7])
            if self._parents[same] == parent and stored == values:
                return True
            same -= 1
        if at == len(stamps):
            stamps.append(stamp)
            self._parents.append(parent)
            self._values.extend(values)
        else:
            stamps.insert(at, stamp)
            self._parents.insert(at, parent)
            self._values[at * 7 : at * 7] = array('d', values)
        return True

    def _prune(self, latest: int) -> None:
        """Drop samples more than the cache length older than `latest`."""
        start = bisect_left(self._stamps, latest - self._cache_ns, self._start)
        self._start = start
        if start >= _COMPACT_AT and start * 2 >= len(self._stamps):
            del self._stamps[:start]
            del self._parents[:start]
            del self._values[: start * 7]
            self._start = 0

    def clear(self) -> None:
        """Forget every sample."""
        self._stamps = array('q')
        self._parents = array('q')
        self._values = array('d')
        self._start = 0

    def _sample(self, i: int) -> Sample:
        v = self._values[i * 7 : i * 7 + 7]
        return (self._parents[i], (v[0], v[1], v[2]), (v[3], v[4], v[5], v[6]))

    def find(self, ns: int) -> tuple[int, int, CacheError | None, str]:
        """Indexes (older, newer) of the samples around `ns` (equal when one sample answers;
        0 means the newest), or an error with tf2's message."""
        stamps = self._stamps
        first, end = self._start, len(stamps)
        if first == end:
            return -1, -1, CacheError.NO_DATA, ''
        if ns == 0:
            return end - 1, end - 1, None, ''
        latest, earliest = stamps[end - 1], stamps[first]
        if end - first == 1:
            if latest == ns:
                return first, first, None, ''
            return (
                -1,
                -1,
                CacheError.NO_DATA,
                (
                    f'Lookup would require extrapolation at time {display_time(ns)}, '
                    f'but only time {display_time(latest)} is in the buffer'
                ),
            )
        if ns == latest:
            return end - 1, end - 1, None, ''
        if ns == earliest:
            return first, first, None, ''
        if ns > latest:
            return (
                -1,
                -1,
                CacheError.FORWARD,
                (
                    'Lookup would require extrapolation into the future.  Requested time '
                    f'{display_time(ns)} but the latest data is at time {display_time(latest)}'
                ),
            )
        if ns < earliest:
            return (
                -1,
                -1,
                CacheError.BACKWARD,
                (
                    'Lookup would require extrapolation into the past.  Requested time '
                    f'{display_time(ns)} but the earliest data is at time {display_time(earliest)}'
                ),
            )
        older = bisect_right(stamps, ns, first) - 1
        return older, older + 1, None, ''

    def get(self, ns: int) -> tuple[Sample | None, CacheError | None, str]:
        """The frame at `ns` (0: the newest), interpolated between the samples around it."""
        older, newer, error, message = self.find(ns)
        if error is not None:
            return None, error, message
        one = self._sample(older)
        if newer == older:
            return one, None, ''
        parent = self._parents[newer]
        if parent != one[0]:  # the parent changed in between: the older sample holds
            return one, None, ''
        two = self._sample(newer)
        t0, t1 = self._stamps[older], self._stamps[newer]
        ratio = (ns - t0) / (t1 - t0)
        return (parent, lerp(one[1], two[1], ratio), slerp(one[2], two[2], ratio)), None, ''

    def parent(self, ns: int) -> tuple[int, CacheError | None, str]:
        """The parent at `ns`, or 0 and why not."""
        older, _newer, error, message = self.find(ns)
        if error is not None:
            return 0, error, message
        return self._parents[older], None, ''

    def latest(self) -> tuple[int, int]:
        """(stamp, parent) of the newest sample; (0, 0) when empty."""
        if len(self._stamps) == self._start:
            return 0, 0
        return self._stamps[-1], self._parents[-1]

    def oldest_stamp(self) -> int:
        """The oldest stamp kept; 0 when empty."""
        return self._stamps[self._start] if len(self._stamps) > self._start else 0


class StaticCache:
    """A frame that never moves: its one transform holds at any time."""

    __slots__ = ('_sample',)

    def __init__(self) -> None:
        self._sample: Sample = (0, (0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0))

    def __len__(self) -> int:
        return 1

    def insert(self, stamp: int, parent: int, translation: Vec, rotation: Quat) -> bool:
        """Replace the transform (a static frame's newest word is its only one)."""
        self._sample = (parent, translation, rotation)
        return True

    def clear(self) -> None:
        """A static frame survives a clear, as in tf2."""

    def get(self, ns: int) -> tuple[Sample | None, CacheError | None, str]:
        """The transform, whatever the time."""
        return self._sample, None, ''

    def parent(self, ns: int) -> tuple[int, CacheError | None, str]:
        """The parent, whatever the time."""
        return self._sample[0], None, ''

    def latest(self) -> tuple[int, int]:
        """(0, parent): a static frame has no time of its own."""
        return 0, self._sample[0]

    def oldest_stamp(self) -> int:
        """0: a static frame has no time of its own."""
        return 0


FrameCache = TimeCache | StaticCache
