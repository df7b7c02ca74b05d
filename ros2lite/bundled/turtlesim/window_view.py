"""turtlesim in a tkinter window: the background, the pen trails and the turtles, 500x500 px
as turtlesim's own window.

The window runs on the main thread and only reads the node: the latest `Frame` and the
strokes the canvas logged since the last redraw (painted into a transparent photo image laid
over the background, so trails cost one small `put` each and never pile up as items). A
redraw that falls behind just skips frames; the simulation does not wait for it.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import TYPE_CHECKING

from ros2lite.bundled.display import open_window
from ros2lite.bundled.turtlesim import sim, sprite

if TYPE_CHECKING:
    from ros2lite.bundled.turtlesim.node import Frame, TurtlesimNode

FRAME_SECONDS = sim.DT  # redraw as often as the world steps


class WindowView:
    """A `TurtleSim` window on the node's world; `run(stop)` until closed or `stop()`."""

    def __init__(self, node: TurtlesimNode) -> None:
        import tkinter

        self.root = open_window('turtlesim', 'TurtleSim')
        self.node = node
        self.world: sim.World = node.world
        self.root.resizable(False, False)
        self.background = self.world.background
        self.canvas = tkinter.Canvas(
            self.root,
            width=sim.CANVAS_PX,
            height=sim.CANVAS_PX,
            highlightthickness=0,
            borderwidth=0,
            background=sprite.hex_colour(self.background),
        )
        self.canvas.pack()
        self.path = tkinter.PhotoImage(width=sim.CANVAS_PX, height=sim.CANVAS_PX)
        self.canvas.create_image(0, 0, image=self.path, anchor='nw')
        self.turtles: dict[str, tuple[int, sim.Pose | None, list[int]]] = {}
        self.closed = False
        self.frames = 0
        self.root.protocol('WM_DELETE_WINDOW', self._close)
        # what is on the canvas already (drawn before the window opened), then what follows
        self.world.canvas.keep_strokes = True
        self._paint_existing()

    def _close(self) -> None:
        self.closed = True

    def _paint_existing(self) -> None:
        pixels = self.world.canvas.pixels
        size = self.world.canvas.size
        if not any(pixels[3::4]):
            return
        for py in range(size):
            row = py * size * 4
            for px in range(size):
                i = row + px * 4
                if pixels[i + 3]:
                    rgb = (pixels[i], pixels[i + 1], pixels[i + 2])
                    self.path.put(sprite.hex_colour(rgb), to=(px, py, px + 1, py + 1))

    def _draw_strokes(self) -> None:
        size = sim.CANVAS_PX
        for stroke in self.world.canvas.drain():
            if stroke[0] == 'clear':
                self.path.blank()
                continue
            _, x0, y0, x1, y1, rgb, width = stroke
            colour = sprite.hex_colour(rgb)
            for left, top, right, bottom in sim.line_squares(x0, y0, x1, y1, width):
                left, top = max(left, 0), max(top, 0)
                right, bottom = min(right, size), min(bottom, size)
                if left < right and top < bottom:
                    self.path.put(colour, to=(left, top, right, bottom))

    def _draw_turtles(self, frame: Frame) -> None:
        seen = set()
        for t in frame.turtles:
            seen.add(t.name)
            pose = sim.Pose(t.x, t.y, t.theta, 0.0, 0.0)
            known = self.turtles.get(t.name)
            if known is not None and known[0] == t.sprite and known[1] == pose:
                continue
            shapes = sprite.parts(t.x, t.y, t.theta, sim.METER_PX, sim.HEIGHT)
            if known is None or known[0] != t.sprite:
                if known is not None:
                    self.canvas.delete(*known[2])
                fills = sprite.colours(t.sprite)
                items = [
                    self.canvas.create_polygon(
                        flat, fill=sprite.hex_colour(fills[role]), outline='#202020'
                    )
                    for flat, role in shapes
                ]
                self.turtles[t.name] = (t.sprite, pose, items)
            else:
                for item, (flat, _) in zip(known[2], shapes, strict=True):
                    self.canvas.coords(item, *flat)
                self.turtles[t.name] = (t.sprite, pose, known[2])
        for name in [n for n in self.turtles if n not in seen]:
            self.canvas.delete(*self.turtles.pop(name)[2])

    def draw(self) -> None:
        """Bring the window up to date with the world (one frame)."""
        frame = self.node.frame
        if frame.background != self.background:
            self.background = frame.background
            self.canvas.configure(background=sprite.hex_colour(self.background))
        self._draw_strokes()
        self._draw_turtles(frame)
        self.frames += 1
        self.node.render_frames = self.frames

    def run(self, stop: Callable[[], bool]) -> None:
        """Redraw every frame until the window is closed or `stop()`; Ctrl-C raises
        KeyboardInterrupt here, as everywhere on the main thread."""
        next_frame = time.monotonic()
        try:
            while not self.closed and not stop():
                self.draw()
                self.root.update()
                next_frame += FRAME_SECONDS
                delay = next_frame - time.monotonic()
                if delay > 0:
                    time.sleep(delay)
                else:
                    next_frame = time.monotonic()  # behind: skip, never catch up in a burst
        finally:
            self.world.canvas.keep_strokes = False
            self.root.destroy()
