"""A top-down scene, as the terminal view and the window both draw it: what the robot's topics
say, placed by tf in one fixed frame, reduced to the floor plane. No drawing here.

Messages come in as CDR bytes and each topic keeps only its newest (a flood of scans replaces
one slot, it never grows a queue); they are decoded when a snapshot is taken, at the views'
bounded pace. The fixed frame, unless given, is the root of the robot's tf tree.
"""

from __future__ import annotations

import math
import threading
import time
from collections import deque
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field

from ros2lite.monitor.plane import (
    IDENTITY,
    Affine,
    Footprint,
    Point,
    Pose2,
    apply,
    invert,
    planar,
    pose_affine,
    pose_of,
    then,
    yaw_of,
)
from ros2lite.msgs.nav_msgs.msg import OccupancyGrid, Odometry, Path
from ros2lite.msgs.sensor_msgs.msg import LaserScan
from ros2lite.msgs.std_msgs.msg import String
from ros2lite.serialization import deserialize_message
from ros2lite.tf2.core import BufferCore
from ros2lite.tf2.errors import TransformException
from ros2lite.urdf import UrdfError, Visual, parse_urdf

__all__ = [
    'FRAME_LIMIT',
    'FREE_CELL',
    'KINDS',
    'OCCUPIED_CELL',
    'OFF_GRID',
    'UNKNOWN_CELL',
    'Footprint',
    'Grid',
    'Scene',
    'Snapshot',
    'Viewport',
    'footprint_from_urdf',
    'yaw_of',
]


# the topic kinds the scene shows, by message type
KINDS: dict[str, type] = {
    'sensor_msgs/msg/LaserScan': LaserScan,
    'nav_msgs/msg/OccupancyGrid': OccupancyGrid,
    'nav_msgs/msg/Path': Path,
    'nav_msgs/msg/Odometry': Odometry,
    'std_msgs/msg/String': String,  # /robot_description only
}
TRAIL_POINTS = 2000  # the trail keeps this many positions, newest last
TRAIL_STEP = 0.02  # m: a new trail point once the robot moved this far
TREE_SECONDS = 0.5  # how often the frame tree is read again
BASE_FRAMES = ('base_footprint', 'base_link')
FRAME_LIMIT = 200  # tf frames drawn at most (a tree of thousands would be a smudge)


OFF_GRID, UNKNOWN_CELL, FREE_CELL, OCCUPIED_CELL = range(4)  # what Grid.classes says
FLAT = 0.1  # rad: a shape tilted more than this is not the robot's outline from above


def footprint_from_urdf(text: str, base: str) -> Footprint | None:
    """The robot's outline from above: the largest upright box or cylinder of the base link
    (collision shapes first, then visuals), or of the links fixed to it (base_footprint ->
    base_link); None when the URDF does not parse or has neither."""
    try:
        robot = parse_urdf(text)
    except UrdfError:
        return None
    start = base if base in robot.links else robot.root
    fixed_children: dict[str, list[tuple[str, Affine]]] = {}
    for joint in robot.joints.values():
        if joint.type == 'fixed':
            offset = pose_affine(joint.xyz[0], joint.xyz[1], joint.rpy[2])
            fixed_children.setdefault(joint.parent, []).append((joint.child, offset))
    best: tuple[float, Footprint] | None = None
    todo: list[tuple[str, Affine]] = [(start, IDENTITY)]
    seen = set()
    while todo:
        name, place = todo.pop(0)
        if name in seen or name not in robot.links:
            continue
        seen.add(name)
        link = robot.links[name]
        for shapes in (link.collisions, link.visuals):
            for shape in shapes:
                found = _outline_of(shape, place)
                if found is not None and (best is None or found[0] > best[0]):
                    best = found
            if best is not None:
                break
        todo.extend((child, then(place, offset)) for child, offset in fixed_children.get(name, []))
    return best[1] if best is not None else None


def _outline_of(shape: Visual, place: Affine) -> tuple[float, Footprint] | None:
    """(area from above, footprint) of an upright box or cylinder placed by `place`."""
    roll, pitch, yaw = shape.rpy
    g = shape.geometry
    if abs(roll) > FLAT or abs(pitch) > FLAT or g.kind not in ('box', 'cylinder'):
        return None
    where = pose_of(then(place, pose_affine(shape.xyz[0], shape.xyz[1], yaw)))
    if g.kind == 'box':
        length, width = g.size[0], g.size[1]
        if length <= 0 or width <= 0:
            return None
        return length * width, Footprint('box', 0.0, length, width, *where)
    if g.radius <= 0:
        return None
    return math.pi * g.radius**2, Footprint('circle', g.radius, 0.0, 0.0, *where)


@dataclass(frozen=True)
class Grid:
    """An occupancy grid placed in the fixed frame: `value_at(x, y)` is the cell's value
    (-1 unknown, 0 free .. 100 occupied), None off the grid."""

    topic: str
    width: int
    height: int
    resolution: float
    to_cells: Affine  # fixed frame -> cell coordinates (in cells)
    corners: tuple[Point, Point, Point, Point]
    data: Sequence[int]

    def classes(
        self,
        dot_to_world: Affine,
        cols: int,
        rows: int,
        cell: tuple[int, int],
        offsets: Sequence[tuple[float, float]],
    ) -> list[int]:
        """For each of `cols` x `rows` cells of `cell` dots (a character, a block of
        pixels): OCCUPIED_CELL if any sample at `offsets` (in dots, the first is the cell's
        middle) falls on an occupied cell of the grid, else FREE_CELL / UNKNOWN_CELL as the
        middle is, else OFF_GRID. One pass of plain arithmetic: it runs for every cell of a
        view whenever the view moves."""
        a, b, c, d, e, f = then(self.to_cells, dot_to_world)
        width, height, data = self.width, self.height, self.data
        cw, ch = cell
        out = [OFF_GRID] * (cols * rows)
        floor = math.floor
        for r in range(rows):
            for k in range(cols):
                x0, y0 = k * cw, r * ch
                verdict = OFF_GRID
                for n, (ox, oy) in enumerate(offsets):
                    px, py = x0 + ox, y0 + oy
                    i = floor(a * px + b * py + c)
                    j = floor(d * px + e * py + f)
                    if 0 <= i < width and 0 <= j < height:
                        v = data[j * width + i]
                        if v >= 50:
                            verdict = OCCUPIED_CELL
                            break
                        if n == 0:
                            verdict = FREE_CELL if v >= 0 else UNKNOWN_CELL
                out[r * cols + k] = verdict
        return out

    def value_at(self, x: float, y: float) -> int | None:
        a = self.to_cells
        i = math.floor(a[0] * x + a[1] * y + a[2])
        j = math.floor(a[3] * x + a[4] * y + a[5])
        if 0 <= i < self.width and 0 <= j < self.height:
            return int(self.data[j * self.width + i])
        return None


@dataclass
class Snapshot:
    """The scene at one moment, everything in `fixed_frame`."""

    fixed_frame: str
    robot: Pose2 | None = None
    footprint: Footprint = field(default_factory=Footprint)
    trail: list[Point] = field(default_factory=list)
    scans: dict[str, list[Point]] = field(default_factory=dict)
    paths: dict[str, list[Point]] = field(default_factory=dict)
    grids: list[Grid] = field(default_factory=list)
    frames: list[tuple[str, Pose2]] = field(default_factory=list)
    problems: list[str] = field(default_factory=list)

    def bounds(self) -> tuple[float, float, float, float] | None:
        """(xmin, ymin, xmax, ymax) of what there is to show, or None when nothing is."""
        points: list[Point] = [*self.trail]
        for hits in self.scans.values():
            points.extend(hits)
        for path in self.paths.values():
            points.extend(path)
        for grid in self.grids:
            points.extend(grid.corners)
        points.extend((x, y) for _, (x, y, _) in self.frames)
        if self.robot is not None:
            points.extend(self.footprint.outline(self.robot))
        if not points:
            return None
        xs = [p[0] for p in points]
        ys = [p[1] for p in points]
        return (min(xs), min(ys), max(xs), max(ys))


class Viewport:
    """Which part of the floor a view shows: the point at its centre and the metres one dot
    (a braille dot, a window pixel) spans. `auto` fits whatever there is; `follow` keeps the
    robot in the middle; a zoom or pan by hand turns `auto` off."""

    def __init__(self, scale: float = 0.05) -> None:
        self.cx = 0.0
        self.cy = 0.0
        self.scale = scale
        self.auto = True
        self.follow = False

    def to_dot(self, x: float, y: float, width: int, height: int) -> tuple[float, float]:
        """Where (x, y) falls on a `width` x `height` dot canvas (y grows downward there)."""
        return ((x - self.cx) / self.scale + width / 2, height / 2 - (y - self.cy) / self.scale)

    def to_world(self, col: float, row: float, width: int, height: int) -> Point:
        """The floor point under dot (col, row)."""
        return (self.cx + (col - width / 2) * self.scale, self.cy + (height / 2 - row) * self.scale)

    def dot_to_world(self, width: int, height: int) -> Affine:
        """to_world as an affine map (for Grid.classes)."""
        s = self.scale
        return (s, 0.0, self.cx - width / 2 * s, 0.0, -s, self.cy + height / 2 * s)

    def update(self, snap: Snapshot, width: int, height: int) -> None:
        """Fit (auto) or centre on the robot (follow), before a frame is drawn."""
        if self.follow and snap.robot is not None:
            self.cx, self.cy = snap.robot[0], snap.robot[1]
        elif self.auto:
            box = snap.bounds()
            if box is None:
                return
            xmin, ymin, xmax, ymax = box
            self.cx, self.cy = (xmin + xmax) / 2, (ymin + ymax) / 2
            margin = max(4, min(width, height) // 20)
            span = max(
                (xmax - xmin) / max(width - 2 * margin, 1),
                (ymax - ymin) / max(height - 2 * margin, 1),
            )
            self.scale = max(span, 0.005)

    def zoom(self, factor: float) -> None:
        """Closer in (factor > 1) or further out, about the centre."""
        self.scale = min(max(self.scale / factor, 1e-4), 1e4)
        self.auto = False

    def zoom_at(self, factor: float, col: float, row: float, width: int, height: int) -> None:
        """Zoom keeping the floor point under dot (col, row) where it is (a mouse wheel)."""
        x, y = self.to_world(col, row, width, height)
        self.zoom(factor)
        nx, ny = self.to_world(col, row, width, height)
        self.cx += x - nx
        self.cy += y - ny
        self.follow = False

    def pan(self, dcols: float, drows: float) -> None:
        """Move the view by this many dots (right, down)."""
        self.cx += dcols * self.scale
        self.cy -= drows * self.scale
        self.auto = False
        self.follow = False


class Scene:
    """The newest message of each topic, read against `buffer` (a tf buffer some listener
    fills) into Snapshots. `offer` may be called from any thread."""

    def __init__(
        self,
        buffer: BufferCore,
        *,
        fixed_frame: str | None = None,
        base_frame: str | None = None,
        robot_radius: float = 0.2,
    ) -> None:
        self.buffer = buffer
        self.requested_fixed = fixed_frame
        self.requested_base = base_frame
        self.default_footprint = Footprint(radius=robot_radius)
        self.revision = 0
        self._lock = threading.Lock()
        self._raw: dict[str, tuple[str, bytes, int]] = {}  # topic -> (kind, cdr, revision)
        self._decoded: dict[str, tuple[int, object]] = {}
        self._parents: dict[str, str] = {}
        self._tree_read = -math.inf
        self._trail: deque[Point] = deque(maxlen=TRAIL_POINTS)
        self._trail_frame = ''
        self._footprint: tuple[str, str, Footprint] | None = None

    # -- input ------------------------------------------------------------------------------
    def offer(self, topic: str, kind: str, data: bytes) -> None:
        """The newest message of `topic` (of message type `kind`, one of KINDS), undecoded."""
        with self._lock:
            self.revision += 1
            self._raw[topic] = (kind, data, self.revision)

    def held(self) -> int:
        """How many samples wait to be decoded: one a topic at most, whatever the rate."""
        with self._lock:
            return len(self._raw)

    def clear_trail(self) -> None:
        with self._lock:
            self._trail.clear()

    def _latest(self, kind: str) -> list[tuple[str, object]]:
        """(topic, decoded message) of every topic of `kind`, decoding only what is new."""
        with self._lock:
            items = [(t, d, r) for t, (k, d, r) in self._raw.items() if k == kind]
        out = []
        for topic, data, rev in sorted(items, key=lambda item: item[0]):
            known = self._decoded.get(topic)
            if known is None or known[0] != rev:
                try:
                    known = (rev, deserialize_message(data, KINDS[kind]))
                except Exception:  # a sample that does not decode shows nothing
                    known = (rev, None)
                self._decoded[topic] = known
            if known[1] is not None:
                out.append((topic, known[1]))
        return out

    # -- the frame tree ---------------------------------------------------------------------
    def parents(self) -> dict[str, str]:
        """Each frame's parent, as the buffer knows them now (read at most every
        TREE_SECONDS)."""
        now = time.monotonic()
        if now - self._tree_read >= TREE_SECONDS:
            self._tree_read = now
            # the buffer's own map: 3000 frames in milliseconds (through tf2's YAML, 16 s)
            self._parents = self.buffer.frame_parents()
        return self._parents

    @staticmethod
    def root_of(frame: str, parents: dict[str, str]) -> str:
        seen = {frame}
        while frame in parents and parents[frame] not in seen:
            frame = parents[frame]
            seen.add(frame)
        return frame

    def base_frame(self, parents: dict[str, str], odom: Odometry | None) -> str | None:
        """The robot's frame: as asked, else the first of BASE_FRAMES tf knows, else the
        child frame /odom names."""
        if self.requested_base:
            return self.requested_base
        known = set(parents) | set(parents.values())
        for name in BASE_FRAMES:
            if name in known:
                return name
        if odom is not None and odom.child_frame_id:
            return str(odom.child_frame_id)
        return None

    def fixed_frame(self, parents: dict[str, str], base: str | None, fallback: str) -> str:
        """As asked, else the root of the base frame's tree, else the root of the largest
        tree, else `fallback` (the frame a message names)."""
        if self.requested_fixed:
            return self.requested_fixed
        if base is not None and base in parents:
            return self.root_of(base, parents)
        if parents:
            roots: dict[str, int] = {}
            for frame in parents:
                root = self.root_of(frame, parents)
                roots[root] = roots.get(root, 0) + 1
            return max(sorted(roots), key=lambda r: roots[r])
        return fallback

    def _place(self, fixed: str, frame: str, ns: int) -> Affine | None:
        """The floor-plane transform from `frame` to `fixed` at `ns` (0: latest; the latest
        too when tf has nothing at that stamp)."""
        frame = frame.removeprefix('/')
        if frame == fixed:
            return IDENTITY
        for when in (ns, 0) if ns else (0,):
            try:
                return planar(self.buffer.lookup(fixed, frame, when)[0])
            except TransformException:
                continue
        return None

    # -- the snapshot -----------------------------------------------------------------------
    def snapshot(self, show_frames: bool = True) -> Snapshot:
        """Everything, placed in the fixed frame now."""
        parents = self.parents()
        odoms = self._latest('nav_msgs/msg/Odometry')
        odom = odoms[0][1] if odoms else None
        assert odom is None or isinstance(odom, Odometry)
        scans = self._latest('sensor_msgs/msg/LaserScan')
        fallback = 'map'
        for _, msg in [*odoms, *scans]:
            header = getattr(msg, 'header', None)
            if header is not None and header.frame_id:
                fallback = str(header.frame_id).removeprefix('/')
                break
        base = self.base_frame(parents, odom)
        fixed = self.fixed_frame(parents, base, fallback)
        snap = Snapshot(fixed_frame=fixed, footprint=self._robot_footprint(base))
        snap.robot = self._robot(fixed, base, odom, snap.problems)
        self._update_trail(fixed, snap.robot)
        with self._lock:
            snap.trail = list(self._trail)
        for topic, msg in scans:
            assert isinstance(msg, LaserScan)
            hits = self._scan_hits(fixed, msg)
            if hits is None:
                snap.problems.append(f'{topic}: no transform {msg.header.frame_id} -> {fixed}')
            else:
                snap.scans[topic] = hits
        for topic, msg in self._latest('nav_msgs/msg/Path'):
            assert isinstance(msg, Path)
            points = self._path(fixed, msg)
            if points is None:
                snap.problems.append(f'{topic}: no transform {msg.header.frame_id} -> {fixed}')
            else:
                snap.paths[topic] = points
        for topic, msg in self._latest('nav_msgs/msg/OccupancyGrid'):
            assert isinstance(msg, OccupancyGrid)
            grid = self._grid(fixed, topic, msg)
            if grid is None:
                snap.problems.append(f'{topic}: no transform {msg.header.frame_id} -> {fixed}')
            else:
                snap.grids.append(grid)
        if show_frames:
            names = sorted(set(parents) | set(parents.values()))
            if len(names) > FRAME_LIMIT:
                snap.problems.append(f'{len(names)} tf frames: the first {FRAME_LIMIT} drawn')
            for frame in names[:FRAME_LIMIT]:
                place = self._place(fixed, frame, 0)
                if place is not None:
                    snap.frames.append((frame, pose_of(place)))
        return snap

    def _robot(
        self, fixed: str, base: str | None, odom: Odometry | None, problems: list[str]
    ) -> Pose2 | None:
        if base is not None:
            place = self._place(fixed, base, 0)
            if place is not None:
                return pose_of(place)
        if odom is not None:  # no tf for the base: where /odom says it is
            p = odom.pose.pose
            where = self._place(fixed, str(odom.header.frame_id), 0)
            if where is not None:
                q = (p.orientation.x, p.orientation.y, p.orientation.z, p.orientation.w)
                pose = then(where, pose_affine(p.position.x, p.position.y, yaw_of(q)))
                return pose_of(pose)
        if base is not None:
            problems.append(f'robot: no transform {base} -> {fixed}')
        return None

    def _update_trail(self, fixed: str, robot: Pose2 | None) -> None:
        with self._lock:
            if fixed != self._trail_frame:
                self._trail.clear()
                self._trail_frame = fixed
            if robot is None:
                return
            if self._trail:
                lx, ly = self._trail[-1]
                if math.hypot(robot[0] - lx, robot[1] - ly) < TRAIL_STEP:
                    return
            self._trail.append((robot[0], robot[1]))

    def _robot_footprint(self, base: str | None) -> Footprint:
        """From /robot_description's base link when it has a box or a cylinder there;
        otherwise a circle of the robot radius."""
        found = self._latest('std_msgs/msg/String')
        if base is None or not found:
            return self.default_footprint
        text = str(getattr(found[0][1], 'data', ''))
        if self._footprint is None or self._footprint[:2] != (text, base):
            shape = footprint_from_urdf(text, base)
            self._footprint = (text, base, shape or self.default_footprint)
        return self._footprint[2]

    def _scan_hits(self, fixed: str, msg: LaserScan) -> list[Point] | None:
        place = self._place(fixed, str(msg.header.frame_id), _stamp_ns(msg))
        if place is None:
            return None
        low, high = float(msg.range_min), float(msg.range_max)
        a0, step = float(msg.angle_min), float(msg.angle_increment)
        hits = []
        for k, r in enumerate(msg.ranges):
            if math.isfinite(r) and low <= r <= high:
                angle = a0 + k * step
                hits.append(apply(place, r * math.cos(angle), r * math.sin(angle)))
        return hits

    def _path(self, fixed: str, msg: Path) -> list[Point] | None:
        points = []
        for pose in msg.poses:
            frame = str(pose.header.frame_id or msg.header.frame_id)
            place = self._place(fixed, frame, 0)
            if place is None:
                return None
            points.append(apply(place, pose.pose.position.x, pose.pose.position.y))
        return points

    def _grid(self, fixed: str, topic: str, msg: OccupancyGrid) -> Grid | None:
        info = msg.info
        width, height, res = int(info.width), int(info.height), float(info.resolution)
        if width <= 0 or height <= 0 or res <= 0 or len(msg.data) < width * height:
            return None
        place = self._place(fixed, str(msg.header.frame_id), 0)
        if place is None:
            return None
        o = info.origin
        q = (o.orientation.x, o.orientation.y, o.orientation.z, o.orientation.w)
        cells_to_fixed = then(
            then(place, pose_affine(o.position.x, o.position.y, yaw_of(q))),
            (res, 0.0, 0.0, 0.0, res, 0.0),
        )
        a, b, c, d = (apply(cells_to_fixed, i, j) for i, j in _corners(width, height))
        return Grid(topic, width, height, res, invert(cells_to_fixed), (a, b, c, d), msg.data)


def _corners(width: int, height: int) -> Iterable[tuple[int, int]]:
    return ((0, 0), (width, 0), (width, height), (0, height))


def _stamp_ns(msg: LaserScan) -> int:
    stamp = msg.header.stamp
    return int(stamp.sec) * 1_000_000_000 + int(stamp.nanosec)
