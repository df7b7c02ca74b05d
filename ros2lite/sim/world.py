"""The 2D world: an occupancy grid with its distance field, and the outlines rays meet.

A world comes from a map_server map (a PNG, PGM or other picture and its YAML) or from shapes
(walls, boxes, cylinders). The grid and its exact Euclidean distance field (computed once at
load) answer "can the robot stand here" in one lookup; the outlines (the shapes' sides and
circles, or the edges of a map's occupied cells) answer "where does this beam stop, and what
colour is it" exactly (`rays.fan`).
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field
from pathlib import Path

from PIL import Image, UnidentifiedImageError

from ros2lite.sim.errors import SimError
from ros2lite.sim.rays import Outlines
from ros2lite.util.safe_yaml import YamlInputError, load

__all__ = [
    'MAX_CELLS',
    'Box',
    'Cylinder',
    'Grid',
    'Shape',
    'Wall',
    'WorldSpec',
    'build_world',
    'load_map',
]

Rgb = tuple[int, int, int]
WALL_GREY: Rgb = (170, 170, 170)
_INF = float('inf')
MAX_CELLS = 16_000_000
"""The most cells a world's grid may have (a drawn world's extent or a map's picture)."""


@dataclass(frozen=True)
class Wall:
    """A straight wall from (x1, y1) to (x2, y2), `thickness` metres across."""

    x1: float
    y1: float
    x2: float
    y2: float
    thickness: float = 0.1
    rgb: Rgb = WALL_GREY


@dataclass(frozen=True)
class Box:
    """A box centred at (x, y), `sx` by `sy` metres, turned by `yaw`."""

    x: float
    y: float
    sx: float
    sy: float
    yaw: float = 0.0
    rgb: Rgb = WALL_GREY


@dataclass(frozen=True)
class Cylinder:
    """An upright cylinder (a pillar, a table leg) seen from above: a disc."""

    x: float
    y: float
    radius: float
    rgb: Rgb = WALL_GREY


Shape = Wall | Box | Cylinder


@dataclass(frozen=True)
class WorldSpec:
    """A world drawn from shapes: its extent, grid resolution, shapes and wall height."""

    name: str
    xmin: float
    ymin: float
    xmax: float
    ymax: float
    shapes: tuple[Shape, ...]
    resolution: float = 0.02
    wall_height: float = 0.5


@dataclass
class Grid:
    """An occupancy grid: row 0 at `origin_y`, cell (i, j) covers x in [ox+i*res, ox+(i+1)*res).

    `colour[k]` indexes `palette` for occupied cells; `dist[k]` is the metres from cell k's centre
    to the nearest occupied cell's centre (0 on an occupied cell, inf in a world with none).
    """

    width: int
    height: int
    resolution: float
    origin_x: float
    origin_y: float
    occupied: bytearray
    colour: bytearray
    palette: list[Rgb] = field(default_factory=lambda: [WALL_GREY])
    dist: list[float] = field(default_factory=list)
    wall_height: float = 0.5
    name: str = 'world'
    outlines: Outlines = field(default_factory=Outlines)

    def finish(self) -> Grid:
        """Compute the distance field (after the cells are set); returns self."""
        self.dist = _distance_field(self.occupied, self.width, self.height, self.resolution)
        return self

    # -- queries -----------------------------------------------------------------------------
    def cell(self, x: float, y: float) -> int:
        """The index of the cell holding (x, y), or -1 outside the grid (and for a point
        that is not finite: nan fails both comparisons)."""
        u = (x - self.origin_x) / self.resolution
        v = (y - self.origin_y) / self.resolution
        if 0 <= u < self.width and 0 <= v < self.height:
            return int(v) * self.width + int(u)
        return -1

    def clearance(self, x: float, y: float) -> float:
        """Metres from (x, y) to the nearest occupied cell (a lower bound, within a cell);
        0 outside the grid, which is solid to a robot."""
        k = self.cell(x, y)
        if k < 0:
            return 0.0
        if self.occupied[k]:
            return 0.0
        return max(0.0, self.dist[k] - 0.5 * self.resolution)


# -- building --------------------------------------------------------------------------------
def build_world(spec: WorldSpec) -> Grid:
    """Draw `spec`'s shapes onto a grid covering its extent."""
    res = spec.resolution
    if res <= 0:
        raise SimError(f'world {spec.name!r}: resolution must be positive, not {res}')
    width = math.ceil((spec.xmax - spec.xmin) / res)
    height = math.ceil((spec.ymax - spec.ymin) / res)
    if width <= 0 or height <= 0 or width * height > MAX_CELLS:
        raise SimError(f'world {spec.name!r}: extent gives a {width}x{height} grid')
    grid = Grid(
        width,
        height,
        res,
        spec.xmin,
        spec.ymin,
        bytearray(width * height),
        bytearray(width * height),
        palette=[],
        wall_height=spec.wall_height,
        name=spec.name,
    )
    for shape in spec.shapes:
        _draw(grid, shape)
    return grid.finish()


def _colour_index(grid: Grid, rgb: Rgb) -> int:
    if rgb not in grid.palette:
        if len(grid.palette) >= 255:
            return 0
        grid.palette.append(rgb)
    return grid.palette.index(rgb)


def _draw(grid: Grid, shape: Shape) -> None:
    """Mark the cells whose centres fall inside `shape`."""
    if isinstance(shape, Cylinder):
        r = shape.radius
        box = (shape.x - r, shape.y - r, shape.x + r, shape.y + r)

        def inside(px: float, py: float) -> bool:
            return (px - shape.x) ** 2 + (py - shape.y) ** 2 <= r * r
    elif isinstance(shape, Box):
        cy, sy = math.cos(shape.yaw), math.sin(shape.yaw)
        hx, hy = shape.sx / 2, shape.sy / 2
        reach = math.hypot(hx, hy)
        box = (shape.x - reach, shape.y - reach, shape.x + reach, shape.y + reach)

        def inside(px: float, py: float) -> bool:
            dx, dy = px - shape.x, py - shape.y
            return abs(dx * cy + dy * sy) <= hx and abs(-dx * sy + dy * cy) <= hy
    else:
        wall = shape
        half = max(wall.thickness, grid.resolution) / 2
        box = (
            min(wall.x1, wall.x2) - half,
            min(wall.y1, wall.y2) - half,
            max(wall.x1, wall.x2) + half,
            max(wall.y1, wall.y2) + half,
        )
        ex, ey = wall.x2 - wall.x1, wall.y2 - wall.y1
        length2 = ex * ex + ey * ey or 1e-12

        def inside(px: float, py: float) -> bool:
            u = max(0.0, min(1.0, ((px - wall.x1) * ex + (py - wall.y1) * ey) / length2))
            return math.hypot(px - wall.x1 - u * ex, py - wall.y1 - u * ey) <= half

    colour = _colour_index(grid, shape.rgb)
    _outline(grid.outlines, shape, colour)
    res = grid.resolution
    i0 = max(0, int((box[0] - grid.origin_x) / res) - 1)
    i1 = min(grid.width - 1, int((box[2] - grid.origin_x) / res) + 1)
    j0 = max(0, int((box[1] - grid.origin_y) / res) - 1)
    j1 = min(grid.height - 1, int((box[3] - grid.origin_y) / res) + 1)
    for j in range(j0, j1 + 1):
        py = grid.origin_y + (j + 0.5) * res
        row = j * grid.width
        for i in range(i0, i1 + 1):
            if inside(grid.origin_x + (i + 0.5) * res, py):
                grid.occupied[row + i] = 1
                grid.colour[row + i] = colour


def _outline(outlines: Outlines, shape: Shape, colour: int) -> None:
    """Add `shape`'s outline: a circle, or the sides of a (wall's) rectangle."""
    if isinstance(shape, Cylinder):
        outlines.circles.append((shape.x, shape.y, shape.radius, colour))
        return
    if isinstance(shape, Box):
        cx, cy, yaw, hx, hy = shape.x, shape.y, shape.yaw, shape.sx / 2, shape.sy / 2
    else:
        cx, cy = (shape.x1 + shape.x2) / 2, (shape.y1 + shape.y2) / 2
        yaw = math.atan2(shape.y2 - shape.y1, shape.x2 - shape.x1)
        hx = math.hypot(shape.x2 - shape.x1, shape.y2 - shape.y1) / 2 + shape.thickness / 2
        hy = shape.thickness / 2
    c, s = math.cos(yaw), math.sin(yaw)
    corners = [
        (cx + c * px - s * py, cy + s * px + c * py)
        for px, py in ((hx, hy), (-hx, hy), (-hx, -hy), (hx, -hy))
    ]
    for n in range(4):
        (x1, y1), (x2, y2) = corners[n], corners[(n + 1) % 4]
        outlines.segments.append((x1, y1, x2, y2, colour))


def _cell_edges(grid: Grid) -> Outlines:
    """The edges between occupied and free cells, merged into runs along rows and columns."""
    w, h, res, ox, oy = grid.width, grid.height, grid.resolution, grid.origin_x, grid.origin_y
    occ = grid.occupied
    out = Outlines()

    def solid(i: int, j: int) -> bool:
        return 0 <= i < w and 0 <= j < h and occ[j * w + i] == 1

    for j in range(h + 1):  # horizontal edges below row j
        start = -1
        for i in range(w + 1):
            edge = i < w and solid(i, j) != solid(i, j - 1)
            if edge and start < 0:
                start = i
            elif not edge and start >= 0:
                y = oy + j * res
                out.segments.append((ox + start * res, y, ox + i * res, y, 0))
                start = -1
    for i in range(w + 1):  # vertical edges left of column i
        start = -1
        for j in range(h + 1):
            edge = j < h and solid(i, j) != solid(i - 1, j)
            if edge and start < 0:
                start = j
            elif not edge and start >= 0:
                x = ox + i * res
                out.segments.append((x, oy + start * res, x, oy + j * res, 0))
                start = -1
    return out


# -- map_server maps -------------------------------------------------------------------------
def load_map(yaml_path: str | Path, wall_height: float = 0.5) -> Grid:
    """A map_server map: its YAML (`image`, `resolution`, `origin`, `negate`,
    `occupied_thresh`) and picture. Unknown cells count as free, as a laser sees them."""
    path = Path(yaml_path)
    try:
        meta = load(path.read_text(encoding='utf-8'), str(path))
    except (OSError, UnicodeDecodeError, YamlInputError) as e:
        raise SimError(f'cannot read map {path}: {e}') from None
    if not isinstance(meta, dict) or 'image' not in meta or 'resolution' not in meta:
        raise SimError(f'map {path}: needs `image` and `resolution` keys')
    try:
        resolution = float(meta['resolution'])
        origin = [float(v) for v in meta.get('origin', [0.0, 0.0, 0.0])]
        negate = bool(int(meta.get('negate', 0)))
        occupied_thresh = float(meta.get('occupied_thresh', 0.65))
    except (TypeError, ValueError) as e:
        raise SimError(f'map {path}: {e}') from None
    if resolution <= 0 or len(origin) < 2:
        raise SimError(f'map {path}: a positive resolution and an [x, y, yaw] origin are needed')
    image_path = path.parent / str(meta['image'])
    try:
        with Image.open(image_path) as picture:
            width, height = picture.size  # from the header: nothing decoded yet
            if width * height > MAX_CELLS:
                raise SimError(
                    f'map {path}: a {width}x{height} image is more than {MAX_CELLS} cells'
                )
            grey = picture.convert('L')
    except (OSError, UnidentifiedImageError, Image.DecompressionBombError) as e:
        raise SimError(f'map {path}: cannot read image {image_path}: {e}') from None
    # map_server's threshold as a lookup table over the 256 grey levels (the same arithmetic
    # per level as per pixel); the picture's top row is the map's far (+y) edge
    table = [
        1 if (v / 255.0 if negate else (255 - v) / 255.0) > occupied_thresh else 0
        for v in range(256)
    ]
    occupied = bytearray(grey.point(table).transpose(Image.Transpose.FLIP_TOP_BOTTOM).tobytes())
    grid = Grid(
        width,
        height,
        resolution,
        origin[0],
        origin[1],
        occupied,
        bytearray(width * height),
        wall_height=wall_height,
        name=path.stem,
    )
    grid.outlines = _cell_edges(grid)
    return grid.finish()


# -- the distance field ----------------------------------------------------------------------
def _distance_field(occupied: bytearray, width: int, height: int, res: float) -> list[float]:
    """Exact Euclidean distances (metres) to the nearest occupied cell: the separable
    lower-envelope transform of Felzenszwalb and Huttenlocher, a column pass then a row pass."""
    if not any(occupied):
        return [_INF] * (width * height)
    big = float((width + height) ** 2 + 1)
    columns = [0.0] * (width * height)
    for i in range(width):
        f = [0.0 if occupied[j * width + i] else big for j in range(height)]
        d = _envelope(f)
        for j in range(height):
            columns[j * width + i] = d[j]
    out = [0.0] * (width * height)
    for j in range(height):
        row = j * width
        d = _envelope(columns[row : row + width])
        for i in range(width):
            out[row + i] = math.sqrt(d[i]) * res if d[i] < big else _INF
    return out


def _envelope(f: Sequence[float]) -> list[float]:
    """The 1D squared distance transform of sampled function `f` (lower envelope of
    parabolas rooted at each sample)."""
    n = len(f)
    d = [0.0] * n
    v = [0] * n
    z = [0.0] * (n + 1)
    k = 0
    z[0], z[1] = -_INF, _INF
    for q in range(1, n):
        fq = f[q] + q * q
        while True:
            p = v[k]
            s = (fq - (f[p] + p * p)) / (2 * (q - p))
            if s > z[k]:
                break
            k -= 1
        k += 1
        v[k] = q
        z[k] = s
        z[k + 1] = _INF
    k = 0
    for q in range(n):
        while z[k + 1] < q:
            k += 1
        p = v[k]
        d[q] = (q - p) * (q - p) + f[p]
    return d


def union_extent(shapes: Iterable[Shape], pad: float = 0.5) -> tuple[float, float, float, float]:
    """The box around `shapes`, `pad` metres wider on every side."""
    xs: list[float] = []
    ys: list[float] = []
    for shape in shapes:
        if isinstance(shape, Wall):
            xs += [shape.x1, shape.x2]
            ys += [shape.y1, shape.y2]
        elif isinstance(shape, Cylinder):
            xs += [shape.x - shape.radius, shape.x + shape.radius]
            ys += [shape.y - shape.radius, shape.y + shape.radius]
        else:
            reach = math.hypot(shape.sx, shape.sy) / 2
            xs += [shape.x - reach, shape.x + reach]
            ys += [shape.y - reach, shape.y + reach]
    if not xs:
        return (-5.0, -5.0, 5.0, 5.0)
    return (min(xs) - pad, min(ys) - pad, max(xs) + pad, max(ys) + pad)
