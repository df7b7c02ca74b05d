"""Where things go: a layered (Sugiyama) layout from left to right, as rqt_graph's dot layout
looks, computed by grandalf (pure Python) instead of by hand. A forest (a tf tree: every
vertex has one parent at most) is laid out here instead, in time linear in its size: grandalf
builds its graph in quadratic time (2,000 frames took minutes), and a tree needs no crossing
minimisation.

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
    tree = _tree_layout(graph, size, layer_gap, node_gap, margin)
    if tree is not None:
        return tree
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


def _tree_layout(
    graph: Graph,
    size: Callable[[str, bool], tuple[float, float]],
    layer_gap: float,
    node_gap: float,
    margin: float,
) -> Layout | None:
    """A forest laid out in layers by depth, each subtree in a span as wide as it needs and
    its root centred over its children; None when `graph` is not a forest."""
    topics = set(graph.topics)
    notes = set(graph.notes)
    names = list(dict.fromkeys((*graph.nodes, *graph.topics, *graph.notes)))
    children: dict[str, list[str]] = {n: [] for n in names}
    parent: dict[str, str] = {}
    for source, target in graph.edges:
        if target in parent or source == target or source not in children:
            return None
        parent[target] = source
        children[source].append(target)
    across = not graph.top_down
    dims = {}
    for n in names:
        w, h = size(n, n in topics)
        dims[n] = (h, w) if across else (w, h)  # along a layer, then across layers
    depth: dict[str, int] = {}
    order: list[str] = []  # parents before children
    for root in (n for n in names if n not in parent):
        depth[root] = 0
        stack = [root]
        while stack:
            n = stack.pop()
            order.append(n)
            for c in children[n]:
                depth[c] = depth[n] + 1
                stack.append(c)
    if len(order) != len(names):
        return None  # a cycle: not a forest
    layers = max(depth.values(), default=-1) + 1
    thick = [0.0] * layers
    for n in names:
        thick[depth[n]] = max(thick[depth[n]], dims[n][1])
    centre = []
    at = 0.0
    for t in thick:
        centre.append(at + t / 2)
        at += t + layer_gap
    span: dict[str, float] = {}
    for n in reversed(order):
        inner = sum(span[c] for c in children[n]) + node_gap * max(len(children[n]) - 1, 0)
        span[n] = max(dims[n][0], inner)
    left: dict[str, float] = {}
    cursor = 0.0
    for root in (n for n in names if n not in parent):
        left[root] = cursor
        cursor += span[root] + node_gap
    along: dict[str, float] = {}
    for n in order:
        inner = sum(span[c] for c in children[n]) + node_gap * max(len(children[n]) - 1, 0)
        at = left[n] + (span[n] - inner) / 2
        for c in children[n]:
            left[c] = at
            at += span[c] + node_gap
        kids = children[n]
        if kids:  # over the middle of its first and last child, as dot draws trees
            first, last = kids[0], kids[-1]
            along[n] = (left[first] + span[first] / 2 + left[last] + span[last] / 2) / 2
        else:
            along[n] = left[n] + span[n] / 2
    for n in reversed(order):  # children are placed after their parent: fix parents up
        kids = children[n]
        if kids:
            along[n] = (along[kids[0]] + along[kids[-1]]) / 2

    def point(a: float, d: float) -> tuple[float, float]:
        return (d + margin, a + margin) if across else (a + margin, d + margin)

    boxes = {}
    for n in names:
        w, h = size(n, n in topics)
        boxes[n] = Box(n, n in topics, *point(along[n], centre[depth[n]]), w, h, n in notes)
    paths = []
    for source, target in graph.edges:
        start = point(along[source], centre[depth[source]] + dims[source][1] / 2)
        end = point(along[target], centre[depth[target]] - dims[target][1] / 2)
        paths.append((source, target, (start, end)))
    width = max((b.x + b.w / 2 for b in boxes.values()), default=0.0) + margin
    height = max((b.y + b.h / 2 for b in boxes.values()), default=0.0) + margin
    return Layout(boxes, tuple(paths), width, height)
