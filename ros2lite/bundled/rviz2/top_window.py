"""The scene from above in a tkinter window, as turtlesim's: the map as an image, laser hits,
paths, the trail, tf frames and the robot's outline as canvas items, redrawn at a bounded
rate from the same Scene the terminal view reads.

The mouse wheel zooms about the pointer, dragging pans; the terminal view's keys work too.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from typing import TYPE_CHECKING

from ros2lite.bundled.rviz2.top_view import (
    FRAME,
    FREE,
    NAME,
    PATH,
    ROBOT,
    SCAN,
    TRAIL,
    Colour,
    TopKeys,
    run_view,
    status,
)
from ros2lite.bundled.terminal import visible

if TYPE_CHECKING:
    import tkinter

    from ros2lite.monitor.scene import Grid, Scene, Snapshot, Viewport

SIZE = 600  # px: the canvas when the window opens
BACKGROUND: Colour = (24, 24, 30)
OCCUPIED_PX: Colour = (235, 235, 235)
UNKNOWN_PX: Colour = (52, 60, 64)
MAP_BLOCK = 3  # px: the map image is sampled at this step, then zoomed
HIT_HALF = 2  # px: a hit is a square this far each side of its point


def hex_colour(c: Colour) -> str:
    return f'#{c[0]:02x}{c[1]:02x}{c[2]:02x}'


class TopWindow(TopKeys):
    """The window on `scene`; `run(ok, period)` until closed, `q`, Ctrl-C or not `ok()`."""

    PAN = 40  # px

    def __init__(self, scene: Scene, frames: bool = True) -> None:
        import tkinter

        from ros2lite.bundled.display import open_window
        from ros2lite.monitor.scene import Viewport

        self.root = open_window('rviz2', 'RViz top view')
        self.scene = scene
        self.view: Viewport = Viewport()
        self.frames = frames
        self.closed = False
        # as large as turtlesim's window and more, but never past a small screen's edge
        side = max(min(SIZE, self.root.winfo_screenwidth() - 40,
                       self.root.winfo_screenheight() - 80), 100)  # fmt: skip
        self.canvas = tkinter.Canvas(
            self.root,
            width=side,
            height=side,
            highlightthickness=0,
            borderwidth=0,
            background=hex_colour(BACKGROUND),
        )
        self.canvas.pack(fill='both', expand=True)
        # width 1: the status line fills the window's width but never asks for more (a long
        # line would widen the window, and the canvas under the pointer with it)
        self.line = tkinter.Label(self.root, anchor='w', width=1, font=('TkFixedFont', 9))
        self.line.pack(fill='x')
        self.map_key: object = None
        self.map_image: tkinter.PhotoImage | None = None
        self.drag: tuple[int, int] | None = None
        self.root.protocol('WM_DELETE_WINDOW', self._close)
        self.canvas.bind('<ButtonPress-1>', self._press)
        self.canvas.bind('<B1-Motion>', self._drag)
        self.canvas.bind('<ButtonRelease-1>', lambda e: self._release())
        self.canvas.bind('<MouseWheel>', lambda e: self._wheel(e.x, e.y, e.delta))
        self.canvas.bind('<Button-4>', lambda e: self._wheel(e.x, e.y, 120))
        self.canvas.bind('<Button-5>', lambda e: self._wheel(e.x, e.y, -120))
        self.root.bind('<Key>', self._key)
        self.frames_drawn = 0

    # -- input ----------------------------------------------------------------------------
    def _close(self) -> None:
        self.closed = True

    def _size(self) -> tuple[int, int]:
        return max(self.canvas.winfo_width(), 8), max(self.canvas.winfo_height(), 8)

    def _press(self, event: tkinter.Event[tkinter.Canvas]) -> None:
        self.drag = (event.x, event.y)

    def _drag(self, event: tkinter.Event[tkinter.Canvas]) -> None:
        if self.drag is not None:
            self.view.pan(self.drag[0] - event.x, self.drag[1] - event.y)
            self.drag = (event.x, event.y)

    def _release(self) -> None:
        self.drag = None

    def _wheel(self, x: int, y: int, delta: int) -> None:
        w, h = self._size()
        self.view.zoom_at(1.25 if delta > 0 else 0.8, x, y, w, h)

    def _key(self, event: tkinter.Event[tkinter.Misc]) -> None:
        key = {'Up': 'up', 'Down': 'down', 'Left': 'left', 'Right': 'right'}.get(
            event.keysym, event.char
        )
        if not self.key(key):
            self.closed = True

    # -- drawing --------------------------------------------------------------------------
    def _map(self, grids: list[Grid], w: int, h: int) -> None:
        """The grids as one image under everything, sampled again only when the view or a
        grid changed."""
        import tkinter

        from ros2lite.monitor.scene import FREE_CELL, OCCUPIED_CELL, OFF_GRID, UNKNOWN_CELL

        NAMES = {UNKNOWN_CELL: 'unknown', FREE_CELL: 'free', OCCUPIED_CELL: 'occupied'}
        view = self.view
        key = (view.cx, view.cy, view.scale, w, h, tuple(id(g.data) for g in grids))
        if key != self.map_key:
            self.map_key = key
            cols, rows = -(-w // MAP_BLOCK), -(-h // MAP_BLOCK)
            paint = {
                None: hex_colour(BACKGROUND),
                'occupied': hex_colour(OCCUPIED_PX),
                'free': hex_colour(FREE),
                'unknown': hex_colour(UNKNOWN_PX),
            }
            kinds: list[str | None] = [None] * (cols * rows)
            where = view.dot_to_world(w, h)
            middle = ((MAP_BLOCK / 2, MAP_BLOCK / 2),)
            for grid in reversed(grids):  # the first grid on top
                classes = grid.classes(where, cols, rows, (MAP_BLOCK, MAP_BLOCK), middle)
                for i, kind in enumerate(classes):
                    if kind != OFF_GRID:
                        kinds[i] = NAMES[kind]
            text_rows = [
                '{' + ' '.join(paint[k] for k in kinds[r * cols : (r + 1) * cols]) + '}'
                for r in range(rows)
            ]
            small = tkinter.PhotoImage(width=cols, height=rows)
            small.put(' '.join(text_rows))
            self.map_image = small.zoom(MAP_BLOCK)
        if self.map_image is not None:
            self.canvas.create_image(0, 0, image=self.map_image, anchor='nw')

    def draw(self) -> Snapshot:
        """One frame: everything deleted and drawn again (a few hundred items)."""
        canvas = self.canvas
        w, h = self._size()
        snap = self.scene.snapshot(show_frames=self.frames)
        view = self.view
        view.update(snap, w, h)
        canvas.delete('all')

        def at(p: tuple[float, float]) -> tuple[float, float]:
            return view.to_dot(p[0], p[1], w, h)

        def polyline(points: list[tuple[float, float]], colour: Colour, width: int = 1) -> None:
            if len(points) >= 2:
                flat = [v for p in points for v in at(p)]
                canvas.create_line(*flat, fill=hex_colour(colour), width=width)

        if snap.grids:
            self._map(snap.grids, w, h)
        polyline(snap.trail, TRAIL, 2)
        for path in snap.paths.values():
            polyline(path, PATH, 2)
        scan = hex_colour(SCAN)
        for hits in snap.scans.values():
            for p in hits:
                px, py = at(p)
                if -4 <= px <= w + 4 and -4 <= py <= h + 4:
                    canvas.create_rectangle(
                        px - HIT_HALF, py - HIT_HALF, px + HIT_HALF, py + HIT_HALF,
                        fill=scan, outline='',
                    )  # fmt: skip
        if snap.robot is not None:
            outline = snap.footprint.outline(snap.robot)
            flat = [v for p in outline[:-1] for v in at(p)]
            canvas.create_polygon(*flat, fill=hex_colour(ROBOT), outline=hex_colour(NAME))
            x, y, yaw = snap.robot
            reach = snap.footprint.reach()
            cx, cy = at((x, y))
            ex, ey = at((x + reach * math.cos(yaw), y + reach * math.sin(yaw)))
            canvas.create_line(cx, cy, ex, ey, fill=hex_colour(BACKGROUND), width=3)
        axis = 24 * view.scale  # 24 px long whatever the zoom
        for name, (x, y, yaw) in snap.frames:
            ox, oy = at((x, y))
            for angle, colour in ((yaw, (230, 60, 60)), (yaw + math.pi / 2, (60, 200, 60))):
                ex, ey = at((x + axis * math.cos(angle), y + axis * math.sin(angle)))
                canvas.create_line(ox, oy, ex, ey, fill=hex_colour(colour), width=2)
            canvas.create_text(
                ox + 6, oy + 6, text=visible(name), anchor='nw', fill=hex_colour(FRAME),
                font=('TkDefaultFont', 8),
            )  # fmt: skip
        self.line.configure(text=status(snap, view))
        self.frames_drawn += 1
        return snap

    def run(self, ok: Callable[[], bool], period: float) -> None:
        """Redraw every `period` s, handling the window's events meanwhile."""
        next_frame = time.monotonic()
        try:
            while not self.closed and ok():
                now = time.monotonic()
                if now >= next_frame:
                    self.draw()
                    next_frame = max(next_frame + period, now)
                self.root.update()
                time.sleep(min(0.02, max(next_frame - time.monotonic(), 0.0)))
        finally:
            self.root.destroy()


def main(argv: list[str] | None = None) -> int:
    """`top_window`: the scene from above in a window."""

    def able() -> None:
        from ros2lite.bundled.display import DisplayError, window_possible

        if not window_possible():
            raise DisplayError('cannot open a window: no display (DISPLAY is not set)')

    return run_view(argv, 'top_window', able, TopWindow)


if __name__ == '__main__':
    raise SystemExit(main())
