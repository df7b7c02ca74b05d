"""rqt_graph on the terminal: the same left-to-right layout in character cells, nodes in
rounded boxes, topics in square ones, arrows drawn with box lines; redrawn when the graph
changes."""

from __future__ import annotations

import sys
import time
from collections.abc import Callable

from ros2lite.bundled.display import DisplayError
from ros2lite.bundled.rqt_graph.layout import Layout, layout
from ros2lite.bundled.rqt_graph.model import Graph
from ros2lite.bundled.terminal import BOLD, RESET, LivePicture, terminal_size


def _cell_size(graph: Graph, name: str) -> tuple[float, float]:
    lines = graph.text(name).split('\n')
    frame = 0 if name in graph.notes else 2  # a note is bare text; the others have a border
    return (max(len(line) for line in lines) + 2 * frame, len(lines) + frame)


def cell_layout(graph: Graph) -> Layout:
    """The graph laid out in terminal cells."""
    gap = 2 if graph.top_down else 4
    return layout(graph, lambda n, _t: _cell_size(graph, n), layer_gap=gap, node_gap=1, margin=1)


def render_lines(graph: Graph, crop: tuple[int, int] | None = None) -> list[list[tuple[str, str]]]:
    """The picture as rows of (character, role) cells; roles: '', 'edge', 'node', 'topic',
    'note'. With `crop` (columns, rows) only that top-left part is drawn: a terminal shows no
    more, and a star of 3,000 frames is a picture of 100,000 columns whose every edge would
    otherwise be drawn across it."""
    lay = cell_layout(graph)
    width, height = int(lay.width) + 2, int(lay.height) + 1
    if crop is not None:
        width, height = min(width, max(crop[0], 0)), min(height, max(crop[1], 0))
    grid = [[(' ', '')] * width for _ in range(height)]

    def xs(start: int, stop: int) -> range:
        return range(max(start, 0), min(stop, width))

    def ys(start: int, stop: int) -> range:
        return range(max(start, 0), min(stop, height))

    def put(x: int, y: int, ch: str, role: str) -> None:
        if 0 <= y < height and 0 <= x < width:
            grid[y][x] = (ch, role)

    boxes = {name: _cells(b.x, b.y, b.w, b.h) for name, b in lay.boxes.items()}
    for source, target, _ in lay.edges if graph.top_down else ():
        sl, _, sr, sb = boxes[source]
        tl, tt, tr, _ = boxes[target]
        x0, x1 = (sl + sr) // 2, (tl + tr) // 2
        y0, y1 = sb + 1, tt - 1
        mid = (y0 + y1) // 2
        for y in ys(y0, mid):
            put(x0, y, '│', 'edge')
        for y in ys(mid, y1 + 1):
            put(x1, y, '│', 'edge')
        if x0 != x1:
            for x in xs(min(x0, x1) + 1, max(x0, x1)):
                put(x, mid, '─', 'edge')
            # children on both sides of their parent share a junction: ┴
            joined = 0 <= mid < height and 0 <= x0 < width and grid[mid][x0][0] in '╰╯┴'
            put(x0, mid, '┴' if joined else '╰' if x1 > x0 else '╯', 'edge')
            put(x1, mid, '╮' if x1 > x0 else '╭', 'edge')
        if not lay.boxes[target].is_note:
            put(x1, y1, '▼', 'edge')
    for source, target, _ in lay.edges if not graph.top_down else ():
        _, st, sr, sb = boxes[source]
        tl, tt, _, tb = boxes[target]
        y0, y1 = (st + sb) // 2, (tt + tb) // 2
        x0 = sr + 1
        x1 = tl - 1
        if x1 <= x0:  # a link back to the left: leave below the boxes and come back
            below = max(sb, tb) + 1
            for x in xs(min(x1, x0), max(x1, x0) + 1):
                put(x, below, '─', 'edge')
            for y in ys(min(y0, below), below):
                put(x0, y, '│', 'edge')
            for y in ys(min(y1, below), below):
                put(x1, y, '│', 'edge')
            put(x0, below, '╯', 'edge')
            put(x1, below, '╰', 'edge')
            put(x1, y1, '▶', 'edge')
            continue
        mid = (x0 + x1) // 2
        for x in xs(x0, mid):
            put(x, y0, '─', 'edge')
        for x in xs(mid, x1):
            put(x, y1, '─', 'edge')
        if y0 != y1:
            for y in ys(min(y0, y1), max(y0, y1)):
                put(mid, y, '│', 'edge')
            put(mid, y0, '╮' if y1 > y0 else '╯', 'edge')
            put(mid, y1, '╰' if y1 > y0 else '╭', 'edge')
        put(x1, y1, '▶', 'edge')
    for name, (left, top, right, bottom) in boxes.items():
        if left >= width or top >= height:
            continue  # outside the crop
        if lay.boxes[name].is_note:  # bare text, centred
            for i, text in enumerate(graph.text(name).split('\n')):
                start = (left + right + 1 - len(text)) // 2
                for j, ch in enumerate(text):
                    put(start + j, top + i, ch, 'note')
            continue
        topic = lay.boxes[name].is_topic
        role = 'topic' if topic else 'node'
        corners = '┌┐└┘' if topic else '╭╮╰╯'
        put(left, top, corners[0], role)
        put(right, top, corners[1], role)
        put(left, bottom, corners[2], role)
        put(right, bottom, corners[3], role)
        for x in xs(left + 1, right):
            put(x, top, '─', role)
            put(x, bottom, '─', role)
        for y in ys(top + 1, bottom):
            put(left, y, '│', role)
            put(right, y, '│', role)
            for x in xs(left + 1, right):
                put(x, y, ' ', role)
        for i, text in enumerate(graph.text(name).split('\n')):
            for j, ch in enumerate(text):
                put(left + 2 + j, top + 1 + i, ch, role)
    return grid


def _cells(x: float, y: float, w: float, h: float) -> tuple[int, int, int, int]:
    left = round(x - w / 2)
    top = round(y - h / 2)
    return left, top, left + int(w) - 1, top + int(h) - 1


def render_text(graph: Graph) -> str:
    """The picture as plain text (no colours)."""
    return '\n'.join(''.join(ch for ch, _ in row).rstrip() for row in render_lines(graph))


def graph_title(graph: Graph) -> str:
    """rqt_graph's title line: what the picture holds."""
    return f'rqt_graph  {len(graph.nodes)} nodes, {len(graph.topics)} topics'


class GraphTerminal:
    """The graph on the terminal, redrawn when it changes; `run` until Ctrl-C. `title` gives
    the line above it (rqt_graph's, or another tool's drawing a graph)."""

    STYLES = {
        '': RESET,
        'edge': '\x1b[0;90m',
        'node': '\x1b[0;1;36m',
        'topic': '\x1b[0;33m',
        'note': '\x1b[0;37m',
    }

    def __init__(self, title: Callable[[Graph], str] = graph_title) -> None:
        if not sys.stdout.isatty():
            raise DisplayError('cannot draw on the terminal: standard output is not a terminal')
        self.title = title

    def picture(self, graph: Graph, width: int = 10_000, height: int = 10_000) -> str:
        """The graph as coloured text, cropped to `width` x `height` cells."""
        title = f'{self.title(graph)}  (Ctrl-C to quit)'
        lines = [BOLD + title[:width] + RESET]
        for row in render_lines(graph, (width, max(height - 1, 0))):
            parts = []
            role = None
            for ch, r in row:  # one colour change per run of the same role
                if r != role:
                    parts.append(self.STYLES[r])
                    role = r
                parts.append(ch)
            lines.append(''.join(parts) + RESET)
        return '\n'.join(lines)

    def run(self, current: Callable[[], Graph], ok: Callable[[], bool], period: float) -> None:
        """Redraw whenever `current()` or the terminal's size changes, every `period` s,
        while `ok()`."""
        shown = None
        with LivePicture(sys.stdout) as live:
            while ok():
                graph = current()
                size = terminal_size(sys.stdout)
                if (graph, size) != shown:
                    shown = (graph, size)
                    live.show(self.picture(graph, *size))
                time.sleep(period)
