"""Ray fans against the world's outlines: a laser sweep or a camera's columns in one pass.

The world's outlines are line segments (walls, box sides, the edges of a map's occupied
cells) and circles (pillars). A fan is cast outline-major: each outline in range is seen
from the sensor under an interval of angles, and only the beams inside that interval are
intersected with it, exactly. A 360-beam sweep so costs about one intersection per beam per
outline facing it, instead of a march along every beam; it is pure Python and needs no grid.
"""

from __future__ import annotations

import math
from bisect import bisect_left, bisect_right
from collections.abc import Sequence
from dataclasses import dataclass, field

__all__ = ['Outlines', 'fan']

_TAU = 2 * math.pi
_INF = float('inf')


@dataclass
class Outlines:
    """Segments as (x1, y1, x2, y2, colour) and circles as (x, y, radius, colour)."""

    segments: list[tuple[float, float, float, float, int]] = field(default_factory=list)
    circles: list[tuple[float, float, float, int]] = field(default_factory=list)


def _beams(angles: Sequence[float], lo: float, hi: float) -> list[range]:
    """Index ranges of the sorted `angles` within [lo, hi] (radians; hi - lo < 2π), trying
    the interval shifted by whole turns so that it overlaps the fan."""
    first = angles[0]
    shift = math.floor((lo - first) / _TAU) * _TAU
    lo -= shift
    hi -= shift
    out = []
    for offset in (0.0, -_TAU, _TAU):
        a, b = lo + offset, hi + offset
        i = bisect_left(angles, a)
        j = bisect_right(angles, b)
        if i < j:
            out.append(range(i, j))
    return out


def fan(
    outlines: Outlines,
    ox: float,
    oy: float,
    yaw: float,
    angles: Sequence[float],
    limit: float,
) -> tuple[list[float], list[int]]:
    """Distances from (ox, oy) along each beam `yaw + angles[k]` (`angles` ascending) to the
    nearest outline within `limit`, and its colour; inf and -1 where nothing is hit."""
    n = len(angles)
    ranges = [_INF] * n
    colours = [-1] * n
    cos, sin = math.cos, math.sin
    dx = [cos(yaw + a) for a in angles]
    dy = [sin(yaw + a) for a in angles]
    atan2, sqrt = math.atan2, math.sqrt
    for x1, y1, x2, y2, colour in outlines.segments:
        ax, ay = x1 - ox, y1 - oy
        ex, ey = x2 - x1, y2 - y1
        # the segment's nearest point to the sensor: out of range means no beam reaches it
        length2 = ex * ex + ey * ey
        u = -(ax * ex + ay * ey) / length2 if length2 > 0 else 0.0
        u = 0.0 if u < 0.0 else 1.0 if u > 1.0 else u
        px, py = ax + u * ex, ay + u * ey
        if px * px + py * py > limit * limit:
            continue
        cross = ax * ey - ay * ex  # > 0: the sensor sees the segment's left side
        if cross == 0.0:
            continue  # seen edge-on
        t1 = atan2(ay, ax) - yaw
        t2 = atan2(ay + ey, ax + ex) - yaw
        span = (t2 - t1) % _TAU
        if span > math.pi:
            t1, span = t2, _TAU - span
        for beams in _beams(angles, t1, t1 + span):
            for k in beams:
                cx, cy = dx[k], dy[k]
                denom = cx * ey - cy * ex
                if denom == 0.0:
                    continue
                t = cross / denom
                if 0.0 < t < ranges[k]:
                    ranges[k] = t
                    colours[k] = colour
    for x, y, r, colour in outlines.circles:
        cx0, cy0 = x - ox, y - oy
        d2 = cx0 * cx0 + cy0 * cy0
        d = sqrt(d2)
        if d - r > limit or d <= r:
            continue
        centre = atan2(cy0, cx0) - yaw
        half = math.asin(r / d)
        r2 = r * r
        for beams in _beams(angles, centre - half, centre + half):
            for k in beams:
                b = dx[k] * cx0 + dy[k] * cy0
                disc = r2 - (d2 - b * b)
                if disc < 0.0:
                    continue
                t = b - sqrt(disc)
                if 0.0 < t < ranges[k]:
                    ranges[k] = t
                    colours[k] = colour
    for k in range(n):
        if ranges[k] > limit:
            ranges[k] = _INF
            colours[k] = -1
    return ranges, colours
