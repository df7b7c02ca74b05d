"""The course worlds, drawn by us as 2D shapes after the Gazebo worlds' layouts, and the
lookup that turns a `world:=` argument (a name, a world file, a map YAML) into a grid.

- `turtlebot3_world`: a hexagonal arena, 3x3 pillars 1.1 m apart (radius 0.15 m);
- `turtlebot3_house`: a house of rooms joined by doorways, with furniture;
- `jackal_race`: a walled yard with a slalom of barrels and crates;
- `small_office`: TIAGo's office: a corridor, offices, desks and a meeting table;
- `empty_world`: a floor with nothing on it.
A `.yaml` path is a map_server map; a `.world`/`.sdf` file is read for its boxes and
cylinders (the SDF `<collision>` geometry of models placed in it), seen from above.
"""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from pathlib import Path

from ros2lite.sim.errors import SimError
from ros2lite.sim.world import (
    Box,
    Cylinder,
    Grid,
    Shape,
    Wall,
    WorldSpec,
    build_world,
    load_map,
    union_extent,
)

__all__ = ['WORLDS', 'open_world', 'sdf_shapes']

_WALL = (200, 200, 190)
_PILLAR = (40, 160, 60)
_WOOD = (150, 100, 60)


def _polygon(points: list[tuple[float, float]], thickness: float) -> list[Shape]:
    return [
        Wall(*points[n], *points[(n + 1) % len(points)], thickness=thickness, rgb=_WALL)
        for n in range(len(points))
    ]


def _turtlebot3_world() -> WorldSpec:
    radius = 2.9
    hexagon = [
        (radius * math.cos(math.radians(a)), radius * math.sin(math.radians(a)))
        for a in range(0, 360, 60)
    ]
    shapes = _polygon(hexagon, 0.15)
    shapes += [
        Cylinder(1.1 * i, 1.1 * j, 0.15, rgb=_PILLAR) for i in (-1, 0, 1) for j in (-1, 0, 1)
    ]
    return WorldSpec('turtlebot3_world', -3.2, -2.9, 3.2, 2.9, tuple(shapes), 0.02, 0.5)


def _turtlebot3_house() -> WorldSpec:
    t = 0.15
    shapes: list[Shape] = _polygon([(-7.5, -5.0), (7.5, -5.0), (7.5, 5.0), (-7.5, 5.0)], t)

    def wall(x1: float, y1: float, x2: float, y2: float) -> None:
        shapes.append(Wall(x1, y1, x2, y2, thickness=t, rgb=_WALL))

    # rooms: living room (centre), kitchen (east), two bedrooms (west), a hall (north)
    wall(-4.0, -5.0, -4.0, -1.0)  # west rooms' wall, a doorway from -1.0 to 0.0
    wall(-4.0, 0.0, -4.0, 5.0)
    wall(-7.5, 1.0, -5.5, 1.0)  # between the bedrooms, doorway at -5.5..-4.5
    wall(4.0, -5.0, 4.0, -2.0)  # kitchen wall, doorway at -2.0..-0.8
    wall(4.0, -0.8, 4.0, 2.0)
    wall(4.0, 2.0, 7.5, 2.0)
    wall(-4.0, 2.5, 1.0, 2.5)  # the hall, doorway at 1.0..2.2
    wall(2.2, 2.5, 4.0, 2.5)
    shapes += [
        Box(0.5, 0.5, 1.2, 0.8, 0.0, rgb=_WOOD),  # living-room table
        Box(-1.0, -4.3, 2.0, 0.8, 0.0, rgb=(120, 60, 60)),  # sofa
        Box(6.6, -3.5, 1.4, 0.6, 0.0, rgb=_WOOD),  # kitchen counter
        Cylinder(5.5, 0.0, 0.35, rgb=_WOOD),  # kitchen table
        Box(-6.3, 3.5, 1.6, 2.0, 0.0, rgb=(90, 90, 160)),  # beds
        Box(-6.3, -3.5, 1.6, 2.0, 0.0, rgb=(90, 90, 160)),
        Cylinder(3.0, -3.5, 0.25, rgb=(60, 60, 60)),  # trash can
        Box(-2.0, 4.2, 2.5, 0.5, 0.0, rgb=_WOOD),  # hall shelf
    ]
    return WorldSpec('turtlebot3_house', -7.7, -5.2, 7.7, 5.2, tuple(shapes), 0.03, 1.0)


def _jackal_race() -> WorldSpec:
    # a walled yard with a slalom of barrels and a few crates, the Jackal at its centre
    shapes: list[Shape] = _polygon(
        [(-10.0, -10.0), (10.0, -10.0), (10.0, 10.0), (-10.0, 10.0)], 0.2
    )
    shapes += [
        Cylinder(float(x), 4.0 if x % 4 else -4.0, 0.3, rgb=(200, 90, 30)) for x in range(-8, 9, 2)
    ]
    shapes += [
        Box(5.0, 0.0, 1.0, 1.0, 0.3, rgb=_WOOD),
        Box(-5.0, 1.5, 1.5, 0.8, -0.4, rgb=_WOOD),
        Box(0.0, 7.5, 6.0, 0.4, 0.0, rgb=_WALL),
        Box(0.0, -7.5, 6.0, 0.4, 0.0, rgb=_WALL),
    ]
    return WorldSpec('jackal_race', -10.3, -10.3, 10.3, 10.3, tuple(shapes), 0.05, 1.0)


def _small_office() -> WorldSpec:
    # an office floor: a corridor, four offices off it, desks and a meeting table
    t = 0.12
    shapes: list[Shape] = _polygon([(-6.0, -4.0), (6.0, -4.0), (6.0, 4.0), (-6.0, 4.0)], t)

    def wall(x1: float, y1: float, x2: float, y2: float) -> None:
        shapes.append(Wall(x1, y1, x2, y2, thickness=t, rgb=(230, 225, 210)))

    for x1, x2 in ((-6.0, -4.2), (-3.2, 1.0), (2.0, 6.0)):
        wall(x1, 1.0, x2, 1.0)  # corridor's north side, doors at -4.2..-3.2 and 1.0..2.0
    for x1, x2 in ((-6.0, -1.5), (-0.5, 3.5), (4.5, 6.0)):
        wall(x1, -1.0, x2, -1.0)  # south side, doors at -1.5..-0.5 and 3.5..4.5
    wall(0.0, 1.0, 0.0, 4.0)
    wall(1.5, -1.0, 1.5, -4.0)
    shapes += [
        Box(-4.5, 3.0, 1.4, 0.7, 0.0, rgb=_WOOD),
        Box(3.5, 3.0, 1.4, 0.7, 0.0, rgb=_WOOD),
        Box(-3.0, -2.8, 2.0, 1.0, 0.0, rgb=_WOOD),  # meeting table
        Cylinder(4.0, -2.5, 0.3, rgb=(60, 130, 60)),  # a plant
    ]
    return WorldSpec('small_office', -6.2, -4.2, 6.2, 4.2, tuple(shapes), 0.03, 2.5)


def _empty_world() -> WorldSpec:
    return WorldSpec('empty_world', -25.0, -25.0, 25.0, 25.0, (), 0.1, 0.5)


WORLDS = {
    'turtlebot3_world': _turtlebot3_world,
    'turtlebot3_house': _turtlebot3_house,
    'jackal_race': _jackal_race,
    'small_office': _small_office,
    'pal_office': _small_office,
    'house': _turtlebot3_house,  # TIAGo's house and home: the house drawn for TurtleBot3
    'home': _turtlebot3_house,
    'empty_world': _empty_world,
    'empty': _empty_world,
}
"""Bundled world name -> the function drawing its shapes."""


def open_world(name: str) -> Grid:
    """The grid of world `name`: a bundled world's name (with or without `.world`), a
    map_server YAML, or a Gazebo `.world`/`.sdf` file."""
    stem = Path(name).name.removesuffix('.world')
    if stem in WORLDS and not Path(name).is_file():
        return build_world(WORLDS[stem]())
    path = Path(name)
    if not path.is_file():
        known = ', '.join(sorted(WORLDS))
        raise SimError(f'no world {name!r}: not a file, nor a bundled world ({known})')
    if path.suffix in ('.yaml', '.yml'):
        return load_map(path)
    shapes = sdf_shapes(path)
    xmin, ymin, xmax, ymax = union_extent(shapes, pad=1.0)
    return build_world(WorldSpec(path.stem, xmin, ymin, xmax, ymax, tuple(shapes), 0.03))


def _floats(text: str | None, n: int) -> list[float]:
    values = [float(v) for v in (text or '').split()]
    return (values + [0.0] * n)[:n]


def sdf_shapes(path: Path) -> list[Shape]:
    """The boxes and cylinders of a Gazebo world file, as seen from above: each model's
    `<collision>` geometry placed by the model's, link's and collision's poses (yaw only).
    Geometry lying on the floor (a ground plane, anything under 5 cm tall) is left out."""
    try:
        root = ET.parse(path).getroot()
    except (OSError, ET.ParseError) as e:
        raise SimError(f'cannot read world {path}: {e}') from None
    shapes: list[Shape] = []
    for model in root.iter('model'):
        mx, my, _, _, _, myaw = _floats(model.findtext('pose'), 6)
        for link in model.findall('link'):
            lx, ly, _, _, _, lyaw = _floats(link.findtext('pose'), 6)
            for collision in link.findall('collision'):
                cx, cy, cz, _, _, cyaw = _floats(collision.findtext('pose'), 6)
                shape = _collision_shape(collision, cz)
                if shape is None:
                    continue
                # compose model ∘ link ∘ collision in the plane
                x1, y1, a1 = _compose((mx, my, myaw), (lx, ly, lyaw))
                x, y, yaw = _compose((x1, y1, a1), (cx, cy, cyaw))
                if shape[0] == 'box':
                    sx, sy = shape[1], shape[2]
                    shapes.append(Box(x, y, sx, sy, yaw, rgb=_WALL))
                else:
                    shapes.append(Cylinder(x, y, shape[1], rgb=_PILLAR))
    return shapes


def _collision_shape(collision: ET.Element, z: float) -> tuple[str, float, float] | None:
    geometry = collision.find('geometry')
    if geometry is None:
        return None
    box = geometry.find('box')
    if box is not None:
        sx, sy, sz = _floats(box.findtext('size'), 3)
        if sz < 0.05 or z + sz / 2 < 0.05:
            return None
        return ('box', sx, sy)
    cylinder = geometry.find('cylinder')
    if cylinder is not None:
        length = float(cylinder.findtext('length') or 0.0)
        if length < 0.05:
            return None
        return ('cylinder', float(cylinder.findtext('radius') or 0.0), 0.0)
    return None


def _compose(
    a: tuple[float, float, float], b: tuple[float, float, float]
) -> tuple[float, float, float]:
    c, s = math.cos(a[2]), math.sin(a[2])
    return (a[0] + c * b[0] - s * b[1], a[1] + s * b[0] + c * b[1], a[2] + b[2])
