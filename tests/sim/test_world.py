"""The world's grid, distance field and map loading, held against plain geometry."""

from __future__ import annotations

import math
import random
from pathlib import Path

import pytest
from PIL import Image

from ros2lite.sim.errors import SimError
from ros2lite.sim.world import Box, Cylinder, Grid, Wall, WorldSpec, build_world, load_map


def _world(*shapes: Wall | Box | Cylinder) -> Grid:
    return build_world(WorldSpec('t', -3.0, -3.0, 3.0, 3.0, shapes, 0.04))


def test_distance_field_is_exact_euclidean() -> None:
    rng = random.Random(3)
    w, h = 23, 17
    grid = Grid(w, h, 0.1, 0.0, 0.0, bytearray(w * h), bytearray(w * h))
    solid = rng.sample(range(w * h), 12)
    for k in solid:
        grid.occupied[k] = 1
    grid.finish()
    for k in range(w * h):
        i, j = k % w, k // w
        nearest = min(math.hypot(i - s % w, j - s // w) for s in solid) * 0.1
        assert grid.dist[k] == pytest.approx(nearest)


def test_clearance_sees_shapes_and_the_grid_edge() -> None:
    grid = _world(Cylinder(0.0, 0.0, 0.15), Wall(-2.0, -2.0, 2.0, -2.0, thickness=0.1))
    assert grid.clearance(0.0, 0.0) == 0.0
    assert grid.clearance(1.0, 0.0) == pytest.approx(0.85, abs=0.03)
    assert grid.clearance(0.5, -1.5) == pytest.approx(0.45, abs=0.03)
    assert grid.clearance(10.0, 0.0) == 0.0  # outside the world is solid


def test_map_server_map_top_row_is_far_edge(tmp_path: Path) -> None:
    # 10x6 cells of 0.1 m: black top row (y = 0.5..0.6 m), grey unknown column, white rest
    picture = Image.new('L', (10, 6), 254)
    for i in range(10):
        picture.putpixel((i, 0), 0)
    for j in range(6):
        picture.putpixel((9, j), 205)
    picture.save(tmp_path / 'room.png')
    (tmp_path / 'room.yaml').write_text(
        'image: room.png\nresolution: 0.1\norigin: [-0.5, 0.0, 0.0]\nnegate: 0\n'
        'occupied_thresh: 0.65\nfree_thresh: 0.196\n'
    )
    grid = load_map(tmp_path / 'room.yaml')
    assert (grid.width, grid.height) == (10, 6)
    assert grid.occupied[grid.cell(0.0, 0.55)] == 1
    assert grid.occupied[grid.cell(0.0, 0.05)] == 0
    assert grid.occupied[grid.cell(0.45, 0.05)] == 0  # unknown is free
    # the outline of the black row faces the room at y = 0.5
    from ros2lite.sim.rays import fan

    ranges, _ = fan(grid.outlines, 0.0, 0.1, 0.0, [math.pi / 2], 2.0)
    assert ranges[0] == pytest.approx(0.4)


def test_bad_maps_are_one_line(tmp_path: Path) -> None:
    (tmp_path / 'a.yaml').write_text('resolution: 0.05\n')
    with pytest.raises(SimError, match='needs `image`'):
        load_map(tmp_path / 'a.yaml')
    (tmp_path / 'b.yaml').write_text('image: missing.png\nresolution: 0.05\n')
    with pytest.raises(SimError, match='cannot read image'):
        load_map(tmp_path / 'b.yaml')


def test_a_point_that_is_not_finite_is_outside() -> None:
    grid = _world(Box(0.0, 0.0, 0.5, 0.5))
    assert grid.cell(0.0, 0.0) >= 0
    for x, y in ((math.nan, 0.0), (0.0, math.nan), (math.inf, 0.0), (0.0, -math.inf), (1e308, 0)):
        assert grid.cell(x, y) == -1
        assert grid.clearance(x, y) == 0.0


def test_a_map_picture_past_the_cell_cap_is_one_line(tmp_path: Path) -> None:
    # 4001 x 4000 pixels: one column more than the 16M cells a drawn world may have
    Image.new('L', (4001, 4000), 254).save(tmp_path / 'huge.png')
    (tmp_path / 'huge.yaml').write_text('image: huge.png\nresolution: 0.05\n')
    with pytest.raises(SimError, match=r'a 4001x4000 image is more than 16000000 cells'):
        load_map(tmp_path / 'huge.yaml')


@pytest.mark.parametrize('negate', [0, 1])
def test_every_grey_level_thresholds_as_map_server_says(tmp_path: Path, negate: int) -> None:
    # 256 columns, one per grey level, over 3 rows (the top row darkest-first reversed)
    picture = Image.new('L', (256, 3))
    for v in range(256):
        for j in range(3):
            picture.putpixel((v if j else 255 - v, j), v if j else 255 - v)
    picture.save(tmp_path / 'levels.png')
    (tmp_path / 'levels.yaml').write_text(
        f'image: levels.png\nresolution: 1.0\nnegate: {negate}\noccupied_thresh: 0.65\n'
    )
    grid = load_map(tmp_path / 'levels.yaml')
    for v in range(256):
        p = v / 255.0 if negate else (255 - v) / 255.0
        for j in range(3):
            assert grid.occupied[j * 256 + v] == (p > 0.65), (v, j)
    assert 0 < sum(grid.occupied) < 3 * 256
