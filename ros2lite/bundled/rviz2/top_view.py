"""The scene from above on the terminal (over SSH, in tmux): laser hits, the map, paths, the
trail, tf frames and the robot's outline, in braille dots (2 x 4 a character cell) over the
map's cells as background colours, fitted to the terminal and redrawn at a bounded rate.

Keys: +/- zoom, arrows pan, `f` follows the robot, `a` fits everything again, `t` shows or
hides the tf frames, `c` clears the trail, `q` quits. The node and the scene it fills are
shared with the window (top_window.py).
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from collections.abc import Callable
from itertools import pairwise
from typing import TYPE_CHECKING

from ros2lite.bundled.display import DisplayError, own_arguments
from ros2lite.bundled.terminal import RESET, LivePicture, rgb, terminal_size, visible

if TYPE_CHECKING:
    from ros2lite.monitor.scene import Grid, Scene, Snapshot, Viewport
    from ros2lite.node import Node

Colour = tuple[int, int, int]
SCAN: Colour = (255, 64, 64)
ROBOT: Colour = (64, 200, 255)
TRAIL: Colour = (230, 200, 60)
PATH: Colour = (90, 230, 90)
FRAME: Colour = (200, 130, 255)
NAME: Colour = (170, 170, 170)
OCCUPIED: Colour = (205, 205, 205)
FREE: Colour = (44, 44, 52)
DISCOVER_SECONDS = 1.0
KEYS = '+/- zoom · arrows pan · f follow · a fit · t frames · c clear trail · q quit'
_BITS = ((0x01, 0x08), (0x02, 0x10), (0x04, 0x20), (0x40, 0x80))


# -- the node, shared with the window ---------------------------------------------------------
def parser(prog: str) -> argparse.ArgumentParser:
    """The options both views take."""
    p = argparse.ArgumentParser(prog=prog, description='The robot\'s scene seen from above.')
    p.add_argument(
        '-f', '--fixed-frame', help='the frame to draw in (default: the tf tree\'s root)'
    )
    p.add_argument(
        '-d',
        '--display-config',
        metavar='FILE.rviz',
        help='take the fixed frame and the LaserScan topics of an RViz configuration',
    )
    # rviz2's options for its browser view, which hands `--terminal` over to this one
    for name, kind in (('--host', str), ('--port', int), ('--point-budget', int),
                       ('--image-width', int)):  # fmt: skip
        p.add_argument(name, type=kind, help=argparse.SUPPRESS)
    p.add_argument('--terminal', action='store_true', help=argparse.SUPPRESS)
    p.add_argument('--base-frame', help='the robot\'s frame (default: base_footprint or base_link)')
    p.add_argument('--robot-radius', type=float, default=0.2, help='m, without a URDF footprint')
    p.add_argument('--scan', action='append', default=[], help='a LaserScan topic (default: all)')
    p.add_argument('--rate', type=float, default=10.0, help='redraws a second at most')
    p.add_argument('--no-frames', action='store_true', help='hide the tf frames')
    return p


def rviz_config(path: str) -> tuple[str | None, list[str]]:
    """The fixed frame and the enabled LaserScan displays' topics of a `.rviz` file."""
    from ros2lite.util.safe_yaml import load

    try:
        with open(path, encoding='utf-8') as f:
            data = load(f.read(), path)
    except OSError as e:
        raise ValueError(f'cannot read {path}: {e.strerror or e}') from None
    manager = data.get('Visualization Manager') if isinstance(data, dict) else None
    if not isinstance(manager, dict):
        raise ValueError(f'{path} is not an RViz configuration (no Visualization Manager)')
    options = manager.get('Global Options')
    fixed = options.get('Fixed Frame') if isinstance(options, dict) else None
    scans = []
    for display in manager.get('Displays') or []:
        if not isinstance(display, dict) or not str(display.get('Class', '')).endswith(
            '/LaserScan'
        ):
            continue
        topic = display.get('Topic')
        name = topic.get('Value') if isinstance(topic, dict) else topic
        if isinstance(name, str) and name and display.get('Enabled', True) is not False:
            scans.append(name)
    return (str(fixed) if fixed else None), scans


def check(options: argparse.Namespace) -> None:
    """Bad numbers as one line; a `.rviz` file's fixed frame and scans, where the command
    line does not say."""
    if not (options.robot_radius > 0 and math.isfinite(options.robot_radius)):
        raise ValueError(f'--robot-radius must be a positive number, not {options.robot_radius}')
    if not (0 < options.rate <= 100):
        raise ValueError(f'--rate must be between 0 and 100 redraws a second, not {options.rate}')
    if options.display_config:
        fixed, scans = rviz_config(options.display_config)
        options.fixed_frame = options.fixed_frame or fixed
        options.scan = options.scan or scans


class SceneSource:
    """A node that feeds a Scene: tf through a listener, and every topic of a kind the scene
    shows (as the graph reveals them, or the scans asked for), newest-wins, undecoded."""

    def __init__(self, options: argparse.Namespace, name: str) -> None:
        from ros2lite.monitor.scene import Scene
        from ros2lite.node import Node
        from ros2lite.tf2 import Buffer, TransformListener

        self.node: Node = Node(name)
        self.buffer = Buffer(node=self.node)
        self.listener = TransformListener(self.buffer, self.node)
        self.scene: Scene = Scene(
            self.buffer,
            fixed_frame=(options.fixed_frame or '').lstrip('/') or None,
            base_frame=options.base_frame,
            robot_radius=options.robot_radius,
        )
        self.scans: list[str] = list(options.scan)
        self.subscribed: set[str] = set()
        for topic in self.scans:
            self._subscribe(topic, 'sensor_msgs/msg/LaserScan')
        self._subscribe('/robot_description', 'std_msgs/msg/String')
        self.discover()
        self.node.create_timer(DISCOVER_SECONDS, self.discover)

    def _subscribe(self, topic: str, kind: str) -> None:
        from ros2lite.monitor.scene import KINDS
        from ros2lite.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy

        if topic in self.subscribed:
            return
        self.subscribed.add(topic)
        # maps, descriptions and plans are often published once, latched
        latched = kind in ('nav_msgs/msg/OccupancyGrid', 'std_msgs/msg/String', 'nav_msgs/msg/Path')
        qos = QoSProfile(
            depth=1,  # newest wins: a flood replaces, never queues
            reliability=ReliabilityPolicy.RELIABLE if latched else ReliabilityPolicy.BEST_EFFORT,
            durability=DurabilityPolicy.TRANSIENT_LOCAL if latched else DurabilityPolicy.VOLATILE,
        )
        scene = self.scene

        def arrived(data: bytes) -> None:
            scene.offer(topic, kind, data)

        self.node.create_subscription(KINDS[kind], topic, arrived, qos, raw=True)

    def discover(self) -> None:
        """Subscribe to the graph's new topics of the kinds shown."""
        for topic, types in self.node.get_topic_names_and_types():
            for kind in types:
                if kind == 'std_msgs/msg/String' or kind not in _KIND_NAMES:
                    continue
                if kind == 'sensor_msgs/msg/LaserScan' and self.scans:
                    continue
                self._subscribe(topic, kind)


_KIND_NAMES = (
    'sensor_msgs/msg/LaserScan',
    'nav_msgs/msg/OccupancyGrid',
    'nav_msgs/msg/Path',
    'nav_msgs/msg/Odometry',
)


def status(snap: Snapshot, view: Viewport, extra: str = '') -> str:
    """The line under the picture: frame, robot, scale, mode, counts, problems."""
    parts = [f'fixed {visible(snap.fixed_frame)}']
    if snap.robot is not None:
        x, y, yaw = snap.robot
        parts.append(f'robot {x:.2f},{y:.2f} {math.degrees(yaw):.0f}°')
    parts.append(f'{view.scale:.3g} m/dot')
    parts.append('follow' if view.follow else 'fit' if view.auto else 'fixed view')
    hits = sum(len(h) for h in snap.scans.values())
    if snap.scans:
        parts.append(f'{hits} hits')
    if snap.grids:
        parts.append(f'{len(snap.grids)} map')
    if snap.paths:
        parts.append(f'{len(snap.paths)} path')
    if snap.problems:
        parts.append(visible(snap.problems[0]))
    if extra:
        parts.append(extra)
    return '  '.join(parts)


# -- the dot canvas ---------------------------------------------------------------------------
class DotCanvas:
    """`cols` x `rows` character cells of 2 x 4 braille dots: a foreground colour per cell
    (the last layer drawn there), an optional background colour, and text that replaces
    dots."""

    def __init__(self, cols: int, rows: int) -> None:
        self.cols, self.rows = cols, rows
        self.width, self.height = cols * 2, rows * 4
        self.bits = [0] * (cols * rows)
        self.fg: list[Colour | None] = [None] * (cols * rows)
        self.bg: list[Colour | None] = [None] * (cols * rows)
        self.text: dict[int, tuple[str, Colour]] = {}

    def dot(self, x: float, y: float, colour: Colour) -> None:
        px, py = math.floor(x), math.floor(y)
        if 0 <= px < self.width and 0 <= py < self.height:
            cell = (py >> 2) * self.cols + (px >> 1)
            self.bits[cell] |= _BITS[py & 3][px & 1]
            self.fg[cell] = colour

    def line(self, a: tuple[float, float], b: tuple[float, float], colour: Colour) -> None:
        clipped = _clip(a, b, self.width, self.height)
        if clipped is None:
            return
        (x0, y0), (x1, y1) = clipped
        steps = max(1, math.ceil(max(abs(x1 - x0), abs(y1 - y0))))
        for k in range(steps + 1):
            t = k / steps
            self.dot(x0 + (x1 - x0) * t, y0 + (y1 - y0) * t, colour)

    def label(self, x: float, y: float, text: str, colour: Colour) -> None:
        """`text` beside dot (x, y): right of it (past a frame's axes), else below, else
        above, wherever its first cells are empty; it stops short of anything drawn (a name
        never hides data)."""
        col, row = math.floor(x / 2), math.floor(y / 4)
        places = ((col + 4, row), (col + 7, row), (col + 1, row + 1), (col + 1, row - 1),
                  (col + 1, row + 2), (col + 1, row - 2))  # fmt: skip
        for c, r in places:
            if not 0 <= r < self.rows or not 0 <= c < self.cols:
                continue
            start = r * self.cols + c
            head = range(start, start + min(len(text), 3, self.cols - c))
            if any(self.bits[i] or i in self.text for i in head):
                continue
            for k, ch in enumerate(text):
                i = start + k
                if c + k >= self.cols or self.bits[i] or i in self.text:
                    return
                self.text[i] = (ch, colour)
            return

    def lines(self) -> list[str]:
        """The cells as terminal text, one string a row, colours changed only where they
        change."""
        out = []
        for r in range(self.rows):
            parts: list[str] = []
            last: tuple[Colour | None, Colour | None] | None = None
            for c in range(self.cols):
                i = r * self.cols + c
                written = self.text.get(i)
                fg: Colour | None
                if written is not None:
                    ch, fg = written[0], written[1]
                else:
                    bits = self.bits[i]
                    ch = chr(0x2800 + bits) if bits else ' '
                    fg = self.fg[i] if bits else None
                bg = self.bg[i]
                if (fg, bg) != last:
                    parts.append(RESET + (rgb(fg or NAME, bg) if fg or bg else ''))
                    if fg is None and bg is not None:  # a background alone
                        parts[-1] = RESET + f'\x1b[48;2;{bg[0]};{bg[1]};{bg[2]}m'
                    last = (fg, bg)
                parts.append(ch)
            out.append(''.join(parts) + RESET)
        return out


def _clip(
    a: tuple[float, float], b: tuple[float, float], width: int, height: int
) -> tuple[tuple[float, float], tuple[float, float]] | None:
    """Segment a-b cut to the canvas (Liang-Barsky), or None when it misses it."""
    (x0, y0), (x1, y1) = a, b
    dx, dy = x1 - x0, y1 - y0
    t0, t1 = 0.0, 1.0
    for p, q in ((-dx, x0), (dx, width - 1 - x0), (-dy, y0), (dy, height - 1 - y0)):
        if p == 0:
            if q < 0:
                return None
            continue
        t = q / p
        if p < 0:
            t0 = max(t0, t)
        else:
            t1 = min(t1, t)
        if t0 > t1:
            return None
    return (x0 + t0 * dx, y0 + t0 * dy), (x0 + t1 * dx, y0 + t1 * dy)


# where in a character cell the map is sampled, in dots: the middle first, then the corners
CELL_SAMPLES = ((1.0, 2.0), (0.5, 0.5), (1.5, 0.5), (0.5, 3.5), (1.5, 3.5))


class MapCells:
    """The map's cell colours of the last frame, and what they were computed for."""

    def __init__(self) -> None:
        self.key: object = None
        self.colours: list[Colour | None] = []


def _grid_backgrounds(
    canvas: DotCanvas, grids: list[Grid], view: Viewport, cache: MapCells
) -> None:
    """Each cell's map colour: occupied if any of its samples is, else free if its middle
    is; computed again only when the view, the size or a grid changed."""
    from ros2lite.monitor.scene import FREE_CELL, OCCUPIED_CELL

    key = (view.cx, view.cy, view.scale, canvas.cols, canvas.rows, [id(g.data) for g in grids])
    if cache.key != key:
        colours: list[Colour | None] = [None] * (canvas.cols * canvas.rows)
        where = view.dot_to_world(canvas.width, canvas.height)
        for grid in reversed(grids):  # the first grid on top
            classes = grid.classes(where, canvas.cols, canvas.rows, (2, 4), CELL_SAMPLES)
            for i, kind in enumerate(classes):
                if kind == OCCUPIED_CELL:
                    colours[i] = OCCUPIED
                elif kind == FREE_CELL:
                    colours[i] = FREE
        cache.key, cache.colours = key, colours
    canvas.bg = list(cache.colours)


def draw(snap: Snapshot, view: Viewport, canvas: DotCanvas, cache: MapCells | None = None) -> None:
    """The snapshot's layers on `canvas`, the robot last (on top); `cache` keeps the map's
    cells from one frame to the next."""
    w, h = canvas.width, canvas.height

    def at(p: tuple[float, float]) -> tuple[float, float]:
        return view.to_dot(p[0], p[1], w, h)

    if snap.grids:
        _grid_backgrounds(canvas, snap.grids, view, MapCells() if cache is None else cache)
    for a, b in pairwise(snap.trail):
        canvas.line(at(a), at(b), TRAIL)
    for path in snap.paths.values():
        for a, b in pairwise(path):
            canvas.line(at(a), at(b), PATH)
    axis = 3 * view.scale * 2  # 6 dots long whatever the zoom
    for _, (x, y, yaw) in snap.frames:
        origin = at((x, y))
        canvas.line(origin, at((x + axis * math.cos(yaw), y + axis * math.sin(yaw))), FRAME)
        canvas.line(origin, at((x - axis * math.sin(yaw), y + axis * math.cos(yaw))), FRAME)
    for hits in snap.scans.values():
        for p in hits:
            canvas.dot(*at(p), SCAN)
    if snap.robot is not None:
        outline = snap.footprint.outline(snap.robot)
        for a, b in pairwise(outline):
            canvas.line(at(a), at(b), ROBOT)
        x, y, yaw = snap.robot
        reach = snap.footprint.reach()
        canvas.line(at((x, y)), at((x + reach * math.cos(yaw), y + reach * math.sin(yaw))), ROBOT)
    # the frames' names last, where nothing else is drawn
    for name, (x, y, _) in snap.frames:
        origin = at((x, y))
        canvas.label(origin[0], origin[1], visible(name)[:24], NAME)


def picture(
    scene: Scene, view: Viewport, cols: int, rows: int, frames: bool, cache: MapCells | None = None
) -> str:
    """One frame of the terminal: the canvas, then the status line and the keys."""
    snap = scene.snapshot(show_frames=frames)
    canvas = DotCanvas(max(cols, 4), max(rows - 2, 2))
    view.update(snap, canvas.width, canvas.height)
    draw(snap, view, canvas, cache)
    lines = canvas.lines()
    lines.append(status(snap, view)[:cols])
    lines.append(KEYS[:cols])
    return '\n'.join(lines)


class TopKeys:
    """The keys both views take (see `KEYS`), acting on `view`, `scene` and `frames`; an arrow
    pans `PAN` of the view's units (character cells here, pixels in the window)."""

    PAN = 8
    scene: Scene
    view: Viewport
    frames: bool

    def key(self, key: str) -> bool:
        """Act on one key (`up`, `down`, `left`, `right` for the arrows); False when it asks
        to quit."""
        view = self.view
        if key in ('q', 'Q'):
            return False
        if key in ('+', '='):
            view.zoom(1.5)
        elif key in ('-', '_'):
            view.zoom(1 / 1.5)
        elif key in ('up', 'down', 'left', 'right'):
            dx, dy = {'up': (0, -1), 'down': (0, 1), 'left': (-1, 0), 'right': (1, 0)}[key]
            view.pan(dx * self.PAN, dy * self.PAN)
        elif key == 'f':
            view.follow = not view.follow
        elif key == 'a':
            view.auto, view.follow = True, False
        elif key == 't':
            self.frames = not self.frames
        elif key == 'c':
            self.scene.clear_trail()
        return True

    def run(self, ok: Callable[[], bool], period: float) -> None:
        """Show the scene every `period` s and take keys, until quit or not `ok()`."""
        raise NotImplementedError


class TopTerminal(TopKeys):
    """The view on stdout, keys from stdin; `run(ok)` until `q`, Ctrl-C or not `ok()`."""

    def __init__(self, scene: Scene, frames: bool = True) -> None:
        from ros2lite.monitor.scene import Viewport

        if not sys.stdout.isatty():
            raise DisplayError('cannot draw on the terminal: standard output is not a terminal')
        self.scene = scene
        self.view = Viewport()
        self.frames = frames
        self.cache = MapCells()

    def run(self, ok: Callable[[], bool], period: float) -> None:
        from ros2lite.bundled.turtlesim.terminal_view import LogLines
        from ros2lite.util.keyboard import Keyboard

        logs = LogLines() if sys.stderr.isatty() else None
        saved_stderr = sys.stderr
        if logs is not None:
            sys.stderr = logs
        keys = True
        drawn = -math.inf
        shown = ''
        try:
            with LivePicture(sys.stdout) as live, Keyboard() as keyboard:
                while ok():
                    if logs is not None and (lines := logs.drain()):
                        live.print_above([visible(line) for line in lines])
                    now = time.monotonic()
                    if now - drawn >= period:
                        drawn = now
                        cols, rows = terminal_size(sys.stdout)
                        text = picture(
                            self.scene, self.view, cols, rows - 1, self.frames, self.cache
                        )
                        if text != shown:
                            live.show(text)
                            shown = text
                    key = None
                    if keys:
                        try:
                            key = keyboard.read(min(period / 2, 0.05))
                        except EOFError:
                            keys = False
                    else:
                        time.sleep(min(period / 2, 0.05))
                    if key is not None:
                        if not self.key(key):
                            return
                        drawn = -math.inf  # show what the key did now
        finally:
            if logs is not None:
                sys.stderr = saved_stderr
                for line in logs.drain():
                    print(visible(line), file=saved_stderr, flush=True)


def run_view(
    argv: list[str] | None,
    prog: str,
    able: Callable[[], None],
    make: Callable[[Scene, bool], TopKeys],
) -> int:
    """`prog`'s main, for both views: the options parsed and checked, `able()` (raising
    DisplayError where the view cannot show) before any node starts, then the view
    `make(scene, frames)` run on node `rviz2_<prog>`'s scene until it ends."""
    from ros2lite.bundled.runner import run_main

    options = parser(prog).parse_args(own_arguments(argv))

    def body() -> None:
        from ros2lite.bundled.teleop.spinning import BackgroundSpin

        check(options)
        able()
        source = SceneSource(options, f'rviz2_{prog}')
        try:
            view = make(source.scene, not options.no_frames)
            with BackgroundSpin(source.node):
                view.run(source.node.context.ok, 1.0 / options.rate)
        finally:
            source.node.destroy_node()

    return run_main(body, argv)


def main(argv: list[str] | None = None) -> int:
    """`top_view`: the scene from above on this terminal."""

    def able() -> None:
        if not sys.stdout.isatty():
            raise DisplayError('cannot draw on the terminal: standard output is not a terminal')

    return run_view(argv, 'top_view', able, TopTerminal)


if __name__ == '__main__':
    raise SystemExit(main())
