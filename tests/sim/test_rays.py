"""Ray fans against outlines: exact distances to segments and circles, wrap-around fans."""

from __future__ import annotations

import math
import random

import pytest

from ros2lite.sim.rays import Outlines, fan
from ros2lite.sim.world import Box, Cylinder, Wall, WorldSpec, build_world


def test_beams_meet_walls_and_pillars_exactly() -> None:
    world = build_world(
        WorldSpec('t', -3, -3, 3, 3, (Wall(-2, -2, 2, -2, 0.1), Cylinder(0, 0, 0.15)), 0.05)
    )
    angles = [-math.pi / 2, 0.0, math.pi / 2]
    ranges, colours = fan(world.outlines, -1.0, 0.0, 0.0, angles, 3.5)
    assert ranges[0] == pytest.approx(1.95)  # the wall's near face
    assert ranges[1] == pytest.approx(0.85)  # the pillar's surface
    assert ranges[2] == math.inf and colours[2] == -1


def test_a_full_sweep_agrees_with_brute_force() -> None:
    rng = random.Random(5)
    shapes = tuple(
        Box(
            rng.uniform(-2, 2),
            rng.uniform(-2, 2),
            rng.uniform(0.1, 0.6),
            rng.uniform(0.1, 0.6),
            rng.uniform(0, 3),
        )
        for _ in range(6)
    ) + tuple(Cylinder(rng.uniform(-2, 2), rng.uniform(-2, 2), 0.2) for _ in range(4))
    outlines = build_world(WorldSpec('t', -3, -3, 3, 3, shapes, 0.05)).outlines
    angles = [n * 6.28 / 359 for n in range(360)]
    ox, oy, yaw = 0.1, -0.2, 2.5
    ranges, _ = fan(outlines, ox, oy, yaw, angles, 3.5)
    for k, a in enumerate(angles):
        # each outline alone, one beam at a time: the nearest hit is the minimum
        best = math.inf
        for seg in outlines.segments:
            alone = Outlines(segments=[seg])
            best = min(best, fan(alone, ox, oy, yaw + a, [0.0], 3.5)[0][0])
        for circle in outlines.circles:
            alone = Outlines(circles=[circle])
            best = min(best, fan(alone, ox, oy, yaw + a, [0.0], 3.5)[0][0])
        assert ranges[k] == pytest.approx(best), k
