"""The graph as files: DOT (for Graphviz; it lays it out itself) and SVG (laid out here)."""

from __future__ import annotations

from xml.sax.saxutils import escape

from ros2lite.bundled.rqt_graph.layout import Layout, layout
from ros2lite.bundled.rqt_graph.model import Graph

FONT_SIZE = 14
CHAR_WIDTH = 8.4  # px per character at FONT_SIZE, for sizing the boxes
BOX_HEIGHT = 36
LINE_HEIGHT = 17  # px between the lines of a label of several
NODE_COLOUR = '#1f4e79'
TOPIC_COLOUR = '#7f3f00'


def _quote(name: str) -> str:
    return '"' + name.replace('\\', '\\\\').replace('"', '\\"') + '"'


def to_dot(graph: Graph) -> str:
    """Graphviz text: nodes as ellipses, topics as boxes, left to right as rqt_graph draws."""
    lines = [
        'digraph rosgraph {',
        '  graph [rankdir=LR];',
        '  node [fontname="sans-serif"];',
    ]
    lines += [f'  {_quote(n)} [shape=ellipse];' for n in graph.nodes]
    lines += [f'  {_quote(t)} [shape=box];' for t in graph.topics]
    lines += [f'  {_quote(a)} -> {_quote(b)};' for a, b in graph.edges]
    lines.append('}')
    return '\n'.join(lines) + '\n'


def pixel_size(text: str, is_topic: bool) -> tuple[float, float]:
    """A label's box in pixels (ellipses need more room than boxes for the same text)."""
    lines = text.split('\n')
    width = max(len(line) for line in lines) * CHAR_WIDTH + (24 if is_topic else 40)
    return (width, BOX_HEIGHT + (len(lines) - 1) * LINE_HEIGHT)


def pixel_layout(graph: Graph) -> Layout:
    """The graph laid out in pixels (the SVG's and the window's sizes)."""
    return layout(
        graph,
        lambda name, is_topic: pixel_size(graph.text(name), is_topic),
        layer_gap=70 if not graph.top_down else 40,
        node_gap=24,
        margin=16,
    )


def to_svg(graph: Graph) -> str:
    """A standalone SVG picture of the graph."""
    lay = pixel_layout(graph)
    width, height = max(lay.width, 120.0), max(lay.height, 60.0)
    out = [
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{width:.0f}" height="{height:.0f}" '
        f'viewBox="0 0 {width:.0f} {height:.0f}" font-family="sans-serif" '
        f'font-size="{FONT_SIZE}">',
        '<defs><marker id="arrow" viewBox="0 0 10 10" refX="10" refY="5" markerWidth="8" '
        'markerHeight="8" orient="auto-start-reverse"><path d="M 0 0 L 10 5 L 0 10 z"/>'
        '</marker></defs>',
        '<rect width="100%" height="100%" fill="white"/>',
    ]
    for source, target, points in lay.edges:
        d = ' '.join(f'{"M" if i == 0 else "L"} {x:.1f} {y:.1f}' for i, (x, y) in enumerate(points))
        out.append(
            f'<path class="edge" data-from={_attr(source)} data-to={_attr(target)} d="{d}" '
            'fill="none" stroke="black" stroke-width="1.2" marker-end="url(#arrow)"/>'
        )
    for box in lay.boxes.values():
        label = escape(box.name)
        if box.is_topic:
            out.append(
                f'<g class="topic" data-name={_attr(box.name)}><rect x="{box.x - box.w / 2:.1f}" '
                f'y="{box.y - box.h / 2:.1f}" width="{box.w:.1f}" height="{box.h:.1f}" '
                f'fill="white" stroke="{TOPIC_COLOUR}" stroke-width="1.5"/>'
            )
        else:
            out.append(
                f'<g class="node" data-name={_attr(box.name)}><ellipse cx="{box.x:.1f}" '
                f'cy="{box.y:.1f}" rx="{box.w / 2:.1f}" ry="{box.h / 2:.1f}" fill="white" '
                f'stroke="{NODE_COLOUR}" stroke-width="1.5"/>'
            )
        out.append(
            f'<text x="{box.x:.1f}" y="{box.y:.1f}" text-anchor="middle" '
            f'dominant-baseline="central">{label}</text></g>'
        )
    out.append('</svg>')
    return '\n'.join(out) + '\n'


def _attr(text: str) -> str:
    return '"' + escape(text, {'"': '&quot;'}) + '"'
