"""turtlesim on the terminal (over SSH too): a live canvas of unicode half blocks, fitted to the
terminal's size, with the log lines scrolling above it.

Each character cell shows two square-ish pixels (the upper half block in one colour on a
background of the other), so an 80x24 terminal gives a 46x46 world. The trails are kept at
that resolution from the strokes the world logs (rebuilt from the full canvas when the
terminal is resized); the turtles are drawn on top each frame. Like the window, this view
only reads the node, on the main thread, at its own pace.
"""

from __future__ import annotations

import math
import sys
import threading
import time
from collections import deque
from collections.abc import Callable
from typing import TYPE_CHECKING

from ros2lite.bundled.display import DisplayError
from ros2lite.bundled.terminal import RESET, LivePicture, rgb, terminal_size
from ros2lite.bundled.turtlesim import sim, sprite

if TYPE_CHECKING:
    from ros2lite.bundled.turtlesim.node import TurtlesimNode

FRAME_SECONDS = 0.05  # 20 redraws a second at most; only when something changed
UPPER_HALF = '\u2580'
SHELL_RADIUS = 0.36  # m: how much of a turtle covers the coarse pixels
HEAD_AHEAD = 0.5  # m


class LogLines:
    """Stands in for stderr while the canvas is live: log lines are queued, and printed above
    the canvas by the view (from any thread; whole lines only)."""

    def __init__(self) -> None:
        self._lock = threading.Lock()
        self._partial = ''
        self._lines: deque[str] = deque()

    def write(self, text: str) -> int:
        """Queue the complete lines of `text` (the rest waits for its newline)."""
        with self._lock:
            text = self._partial + text
            *lines, self._partial = text.split('\n')
            self._lines.extend(lines)
        return len(text)

    def flush(self) -> None:
        """Nothing to do: lines are shown when the view draws."""
        pass

    def isatty(self) -> bool:
        """Loggers may colour their output: it ends up on the terminal."""
        return True

    def drain(self) -> list[str]:
        """The complete lines queued since the last call."""
        with self._lock:
            lines = list(self._lines)
            self._lines.clear()
            return lines

    def rest(self) -> str:
        """What was written after the last newline."""
        with self._lock:
            return self._partial


def picture_text(pixels: list[tuple[int, int, int]], side: int, title: str) -> str:
    """`pixels` (side x side colours) as terminal text, two pixel rows per line (upper half
    blocks coloured top on bottom, one colour change per run), then `title`."""
    lines = []
    for row in range(0, side - 1, 2):
        top = pixels[row * side : (row + 1) * side]
        bottom = pixels[(row + 1) * side : (row + 2) * side]
        parts: list[str] = []
        last = None
        for pair in zip(top, bottom, strict=True):
            if pair != last:
                parts.append(rgb(*pair))
                last = pair
            parts.append(UPPER_HALF)
        lines.append(''.join(parts) + RESET)
    lines.append(title)
    return '\n'.join(lines)


class TerminalView:
    """The live canvas on stdout; `run(stop)` until `stop()` or Ctrl-C."""

    def __init__(self, node: TurtlesimNode) -> None:
        if not sys.stdout.isatty():
            raise DisplayError('cannot draw on the terminal: standard output is not a terminal')
        self.node = node
        self.world: sim.World = node.world
        self.side = 0
        self.trails: list[tuple[int, int, int] | None] = []
        self.frames = 0
        self.world.canvas.keep_strokes = True

    # -- the coarse trail image ------------------------------------------------------------
    def _fit(self) -> int:
        width, height = terminal_size(sys.stdout)
        side = max(4, min(width, 2 * (height - 2)))
        return side - side % 2

    def _rebuild(self, side: int) -> None:
        """Trails at a new size, sampled from the full canvas."""
        self.world.canvas.drain()  # everything logged so far is in the pixels already
        self.side = side
        canvas = self.world.canvas
        full = canvas.size
        pixels = canvas.pixels
        trails: list[tuple[int, int, int] | None] = [None] * (side * side)
        for j in range(side):
            y0, y1 = j * full // side, max((j + 1) * full // side, j * full // side + 1)
            for i in range(side):
                x0, x1 = i * full // side, max((i + 1) * full // side, i * full // side + 1)
                for y in range(y0, y1):
                    start = (y * full + x0) * 4
                    block = pixels[start + 3 : (y * full + x1) * 4 : 4]
                    k = next((n for n, a in enumerate(block) if a), -1)
                    if k >= 0:
                        p = start + 4 * k
                        trails[j * side + i] = (pixels[p], pixels[p + 1], pixels[p + 2])
                        break
        self.trails = trails

    def _apply_strokes(self) -> None:
        side = self.side
        scale = side / sim.CANVAS_PX
        for stroke in self.world.canvas.drain():
            if stroke[0] == 'clear':
                self.trails = [None] * (side * side)
                continue
            _, x0, y0, x1, y1, rgb, _width = stroke
            steps = max(1, int(max(abs(x1 - x0), abs(y1 - y0)) * scale * 2))
            for k in range(steps + 1):
                t = k / steps
                i = int((x0 + (x1 - x0) * t) * scale)
                j = int((y0 + (y1 - y0) * t) * scale)
                if 0 <= i < side and 0 <= j < side:
                    self.trails[j * side + i] = rgb

    # -- a frame ---------------------------------------------------------------------------
    def picture(self) -> str:
        """The canvas as it is now, at the terminal's size."""
        side = self._fit()
        if side != self.side:
            self._rebuild(side)
        else:
            self._apply_strokes()
        frame = self.node.frame
        background = frame.background
        pixels = [background if c is None else c for c in self.trails]
        scale = side / (sim.WIDTH + 1.0 / sim.METER_PX)  # pixels per metre
        for t in frame.turtles:
            colours = sprite.colours(t.sprite)
            self._disk(pixels, t.x, t.y, SHELL_RADIUS, scale, colours['shell'])
            hx = t.x + HEAD_AHEAD * math.cos(t.theta)
            hy = t.y + HEAD_AHEAD * math.sin(t.theta)
            self._disk(pixels, hx, hy, 0.0, scale, colours['skin'])
        count = len(frame.turtles)
        title = f'TurtleSim  {count} turtle{"s" if count != 1 else ""}'
        return picture_text(pixels, side, title[:side])

    def _disk(
        self,
        pixels: list[tuple[int, int, int]],
        x: float,
        y: float,
        radius: float,
        scale: float,
        colour: tuple[int, int, int],
    ) -> None:
        side = self.side
        ci = x * scale
        cj = (sim.HEIGHT - y) * scale
        r = max(radius * scale, 0.5)
        for j in range(int(cj - r), int(cj + r) + 1):
            for i in range(int(ci - r), int(ci + r) + 1):
                if (
                    0 <= i < side
                    and 0 <= j < side
                    and (i + 0.5 - ci) ** 2 + (j + 0.5 - cj) ** 2 <= r * r + 0.5
                ):
                    pixels[j * side + i] = colour

    def run(self, stop: Callable[[], bool]) -> None:
        """Redraw whenever the world changed, at most every FRAME_SECONDS."""
        logs = LogLines() if sys.stderr.isatty() else None
        saved_stderr = sys.stderr
        if logs is not None:
            sys.stderr = logs
        last: object = None
        try:
            with LivePicture(sys.stdout) as live:
                while not stop():
                    lines = logs.drain() if logs is not None else []
                    frame = self.node.frame
                    size = terminal_size(sys.stdout)
                    state = (frame.turtles, frame.background, self.node.revision, size)
                    if lines:
                        live.print_above(lines)
                    if state != last or self.world.canvas.has_strokes():
                        last = state
                        live.show(self.picture())
                        self.frames += 1
                        self.node.render_frames = self.frames
                    time.sleep(FRAME_SECONDS)
        finally:
            self.world.canvas.keep_strokes = False
            if logs is not None:
                sys.stderr = saved_stderr
                rest = logs.drain()
                if logs.rest():
                    rest.append(logs.rest())
                for line in rest:
                    print(line, file=saved_stderr, flush=True)
