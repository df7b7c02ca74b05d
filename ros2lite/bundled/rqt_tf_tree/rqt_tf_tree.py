"""`rqt_tf_tree`: the tf frame tree as it is now, drawn with rqt_graph's layout and views: a
frame per ellipse, top down from the root, each edge labelled with its broadcaster, rate and
most recent transform, and a box with the time the picture was taken; redrawn every second.

In a window when there is a display, on the terminal otherwise; with neither it listens a
second and prints view_frames' Graphviz text once.
"""

from __future__ import annotations

import argparse
import dataclasses
import sys
import time
from collections.abc import Callable
from typing import TYPE_CHECKING

from ros2lite.bundled.display import DisplayError, add_display_argument, choose, own_arguments

if TYPE_CHECKING:
    from ros2lite.bundled.rqt_graph.model import Graph
    from ros2lite.node import Node
    from ros2lite.tf2 import Buffer

REFRESH_SECONDS = 1.0
NO_DATA = 'No tf data received'


def now(node: Node) -> float:
    """The node's clock as seconds (the 'Recorded at time' the tools print)."""
    sec, nsec = node.get_clock().now().seconds_nanoseconds()
    return sec + nsec / 1e9


def tree(buffer: Buffer, recorded_at: float) -> Graph:
    """The picture of what `buffer` holds: the frames, and the legend box beside them."""
    from ros2lite.bundled.tf2_tools.frames import parse, to_graph

    graph = to_graph(parse(buffer.all_frames_as_yaml()))
    legend = f'Recorded at time: {recorded_at}' if graph.nodes else NO_DATA
    return dataclasses.replace(graph, topics=(*graph.topics, legend))


def title(graph: Graph) -> str:
    """The terminal's line above the tree."""
    return f'rqt_tf_tree  {len(graph.nodes)} frames'


def show(display: str, current: Callable[[], Graph], ok: Callable[[], bool]) -> bool:
    """Show the tree where `display` says, redrawn while `ok()`; False when nothing can
    show it (`none`, or `auto` with neither a display nor a terminal)."""
    for kind in choose(display):
        try:
            if kind == 'window':
                from ros2lite.bundled.rqt_graph.window_view import GraphWindow

                GraphWindow('rqt_tf_tree').run(current, ok, REFRESH_SECONDS)
                return True
            if kind == 'terminal':
                from ros2lite.bundled.rqt_graph.terminal_view import GraphTerminal

                GraphTerminal(title).run(current, ok, REFRESH_SECONDS)
                return True
        except DisplayError:
            if display != 'auto':
                raise
    return False


def run(display: str) -> None:
    """Listen to tf with a node of our own (named as rqt's node is) and show the tree."""
    from ros2lite.bundled.runner import rqt_node_name
    from ros2lite.bundled.teleop.spinning import BackgroundSpin
    from ros2lite.bundled.tf2_tools.frames import parse, to_dot
    from ros2lite.node import Node
    from ros2lite.tf2 import Buffer, TransformListener

    node = Node(rqt_node_name())
    buffer = Buffer(node=node)  # with the tf2_frames service, as rqt_tf_tree's buffer
    TransformListener(buffer, node)
    try:
        with BackgroundSpin(node):
            if not show(display, lambda: tree(buffer, now(node)), node.context.ok):
                time.sleep(REFRESH_SECONDS)  # as rqt_tf_tree listens before its first picture
                sys.stdout.write(to_dot(parse(buffer.all_frames_as_yaml()), now(node)) + '\n')
    finally:
        node.destroy_node()


def main(args: list[str] | None = None) -> int:
    """`rqt_tf_tree`'s entry point."""
    from ros2lite.bundled.runner import run_main

    parser = argparse.ArgumentParser(
        prog='rqt_tf_tree', description='Show the tree of tf frames, live.'
    )
    add_display_argument(parser)
    options = parser.parse_args(own_arguments(args))
    return run_main(lambda: run(options.display), args)


if __name__ == '__main__':
    sys.exit(main())
