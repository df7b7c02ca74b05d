"""rqt_graph's files for a known graph: the DOT text exactly, the SVG's shapes, labels and
arrows (laid out left to right, publisher before topic before subscriber)."""

from __future__ import annotations

import xml.etree.ElementTree as ET

from ros2lite.bundled.rqt_graph.model import Graph
from ros2lite.bundled.rqt_graph.output import to_dot, to_svg
from ros2lite.bundled.rqt_graph.terminal_view import render_text
from tests.bundled.rqt_graph.test_model import lesson

SVG = '{http://www.w3.org/2000/svg}'


def test_dot() -> None:
    assert to_dot(lesson()) == (
        'digraph rosgraph {\n'
        '  graph [rankdir=LR];\n'
        '  node [fontname="sans-serif"];\n'
        '  "/teleop_turtle" [shape=ellipse];\n'
        '  "/turtlesim" [shape=ellipse];\n'
        '  "/turtle1/cmd_vel" [shape=box];\n'
        '  "/teleop_turtle" -> "/turtle1/cmd_vel";\n'
        '  "/turtle1/cmd_vel" -> "/turtlesim";\n'
        '}\n'
    )
    odd = Graph(('/a"b',), (), ())
    assert '"/a\\"b" [shape=ellipse];' in to_dot(odd)


def test_svg_shapes_and_left_to_right() -> None:
    root = ET.fromstring(to_svg(lesson()))
    nodes = {g.get('data-name'): g for g in root.iter(f'{SVG}g') if g.get('class') == 'node'}
    topics = {g.get('data-name'): g for g in root.iter(f'{SVG}g') if g.get('class') == 'topic'}
    assert set(nodes) == {'/teleop_turtle', '/turtlesim'}
    assert set(topics) == {'/turtle1/cmd_vel'}
    assert all(g.find(f'{SVG}ellipse') is not None for g in nodes.values())
    assert topics['/turtle1/cmd_vel'].find(f'{SVG}rect') is not None
    labels = {t.text for t in root.iter(f'{SVG}text')}
    assert labels == {'/teleop_turtle', '/turtlesim', '/turtle1/cmd_vel'}

    def x(name: str) -> float:
        shape = (nodes.get(name) or topics[name])[0]
        if shape.tag == f'{SVG}ellipse':
            return float(shape.get('cx'))  # type: ignore[arg-type]
        return float(shape.get('x')) + float(shape.get('width')) / 2  # type: ignore[arg-type]

    assert x('/teleop_turtle') < x('/turtle1/cmd_vel') < x('/turtlesim')
    edges = [p for p in root.iter(f'{SVG}path') if p.get('class') == 'edge']
    assert [(p.get('data-from'), p.get('data-to')) for p in edges] == list(lesson().edges)
    for p in edges:
        assert p.get('marker-end') == 'url(#arrow)'
        points = p.get('d', '').replace('M', '').replace('L', '').split()
        xs = [float(v) for v in points[::2]]
        assert xs[0] < xs[-1]  # arrows point right, into the next layer


def test_terminal_picture() -> None:
    text = render_text(lesson())
    assert '╭────────────────╮    ┌──────────────────┐    ╭────────────╮' in text
    assert '│ /teleop_turtle │───▶│ /turtle1/cmd_vel │───▶│ /turtlesim │' in text
