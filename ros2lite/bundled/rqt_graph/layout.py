"""Where things go: a layered (Sugiyama) layout from left to right, as rqt_graph's dot layout
looks, computed by grandalf (pure Python) instead of by hand.

Sizes are in abstract units the caller picks (pixels for SVG and the window, character cells
for the terminal); each label's box is given by `size(name, is_topic)`.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from ros2lite.bundled.rqt_graph.model import Graph


@dataclass(frozen=True)
class Box:
    """A node or topic: centre (x, y) and size (w, h)."""

    name: str
    is_topic: bool
    x: float
    y: float
    w: float
    h: float
    is_note: bool = False  # bare text (an edge's label), see Graph.notes


@dataclass(frozen=True)
class Layout:
    """Where the boxes and edges of a graph go, and the picture's size."""

    boxes: dict[str, Box]
    edges: tuple[tuple[str, str, tuple[tuple[float, float], ...]], ...]  # source, target, path
    width: float
    height: float


def layout(
    graph: Graph,
    size: Callable[[str, bool], tuple[float, float]],
    layer_gap: float,
    node_gap: float,
    margin: float,
) -> Layout:
    """Lay `graph` out left to right (or top down, as it says): layers `layer_gap` apart,
    boxes `node_gap` apart."""
    from grandalf.graphs import Edge, Vertex
    from grandalf.graphs import Graph as GGraph
    from grandalf.layouts import SugiyamaLayout
    from grandalf.routing import route_with_lines

    across = not graph.top_down

    class View:
        def __init__(self, w: float, h: float) -> None:
            # grandalf lays out top-down; swapping w and h and then x and y gives left-right
            self.w, self.h = (h, w) if across else (w, h)
            self.xy = (0.0, 0.0)

    class EdgeView:
        def __init__(self) -> None:
            self.points: list[tuple[float, float]] = []

        def setpath(self, points: list[tuple[float, float]]) -> None:
            self.points = list(points)

    topics = set(graph.topics)
    notes = set(graph.notes)
    vertices = {}
    for name in (*graph.nodes, *graph.topics, *graph.notes):
        v = Vertex(name)
        v.view = View(*size(name, name in topics))
        vertices[name] = v
    edges = []
    for source, target in graph.edges:
        e = Edge(vertices[source], vertices[target])
        e.view = EdgeView()
        edges.append(e)
    g = GGraph(list(vertices.values()), edges)
    offset = 0.0
    placed: dict[str, tuple[float, float]] = {}
    shift: dict[str, float] = {}  # per vertex: its component's move along grandalf's x
    for component in g.C:
        sug = SugiyamaLayout(component)
        sug.route_edge = route_with_lines
        sug.xspace, sug.yspace = node_gap, layer_gap
        roots = [v for v in component.sV if not v.e_in()]
        sug.init_all(roots=roots or None, optimize=True)
        sug.draw(3)
        xs = [v.view.xy[0] - v.view.w / 2 for v in component.sV]
        top = min(xs)
        for v in component.sV:
            placed[v.data] = (v.view.xy[0] - top + offset, v.view.xy[1])
            shift[v.data] = offset - top
        offset += max(v.view.xy[0] + v.view.w / 2 for v in component.sV) - top + node_gap
    # left to right: transpose (layers become columns); then shift into the margin
    ys = [placed[n][1] - vertices[n].view.h / 2 for n in placed] or [0.0]
    left = min(ys)

    def point(gx: float, gy: float) -> tuple[float, float]:
        return (gy - left + margin, gx + margin) if across else (gx + margin, gy - left + margin)

    boxes = {}
    for name, (gx, gy) in placed.items():
        view = vertices[name].view
        w, h = (view.h, view.w) if across else (view.w, view.h)
        boxes[name] = Box(name, name in topics, *point(gx, gy), w, h, is_note=name in notes)
    paths = []
    for e in edges:
        s, t = e.v[0].data, e.v[1].data
        dx = shift[s]
        points = [point(px + dx, py) for px, py in e.view.points]
        if len(points) < 2:
            points = [(boxes[s].x, boxes[s].y), (boxes[t].x, boxes[t].y)]
        paths.append((s, t, tuple(points)))
    width = max((b.x + b.w / 2 for b in boxes.values()), default=0.0) + margin
    height = max((b.y + b.h / 2 for b in boxes.values()), default=0.0) + margin
    return Layout(boxes, tuple(paths), width, height)
