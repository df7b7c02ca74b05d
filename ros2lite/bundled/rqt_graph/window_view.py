"""rqt_graph in a tkinter window: ellipses for nodes, boxes for topics, arrows between them,
laid out left to right and redrawn when the graph changes."""

from __future__ import annotations

import time
from collections.abc import Callable

from ros2lite.bundled.display import open_window
from ros2lite.bundled.rqt_graph.model import Graph
from ros2lite.bundled.rqt_graph.output import NODE_COLOUR, TOPIC_COLOUR, pixel_layout


class GraphWindow:
    """A window titled `title` (rqt_graph's own, or another tool's drawing a graph); `run`
    until closed, `ok()` turns False or Ctrl-C."""

    def __init__(self, title: str = 'rqt_graph') -> None:
        import tkinter

        self.root = open_window(title, title)
        self.canvas = tkinter.Canvas(self.root, background='white', highlightthickness=0)
        self.canvas.pack(fill='both', expand=True)
        self.closed = False
        self.root.protocol('WM_DELETE_WINDOW', self._close)

    def _close(self) -> None:
        self.closed = True

    def draw(self, graph: Graph) -> None:
        """Draw the graph on the canvas, sized to fit it."""
        lay = pixel_layout(graph)
        c = self.canvas
        c.delete('all')
        width, height = int(max(lay.width, 200)), int(max(lay.height, 100))
        c.configure(width=width, height=height)
        for _, target, points in lay.edges:
            flat = [v for point in points for v in point]
            if lay.boxes[target].is_note:  # an edge's label: the arrow ends past it
                c.create_line(*flat, fill='black', width=1.2)
            else:
                c.create_line(*flat, arrow='last', fill='black', width=1.2)
        for box in lay.boxes.values():
            corners = (box.x - box.w / 2, box.y - box.h / 2, box.x + box.w / 2, box.y + box.h / 2)
            if box.is_note:
                c.create_rectangle(*corners, fill='white', outline='')
            elif box.is_topic:
                c.create_rectangle(*corners, fill='white', outline=TOPIC_COLOUR, width=1.5)
            else:
                c.create_oval(*corners, fill='white', outline=NODE_COLOUR, width=1.5)
            c.create_text(box.x, box.y, text=graph.text(box.name), fill='black', justify='center')

    def run(self, current: Callable[[], Graph], ok: Callable[[], bool], period: float) -> None:
        """Redraw whenever `current()` changes, every `period` s, until closed or not `ok()`."""
        shown = None
        next_check = 0.0
        try:
            while not self.closed and ok():
                now = time.monotonic()
                if now >= next_check:
                    next_check = now + period
                    graph = current()
                    if graph != shown:
                        shown = graph
                        self.draw(graph)
                self.root.update()
                time.sleep(0.05)
        finally:
            self.root.destroy()
