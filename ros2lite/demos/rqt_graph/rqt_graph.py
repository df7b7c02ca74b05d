"""`rqt_graph`: the live ROS graph, nodes as ellipses and topics as boxes, arrows from
publisher to topic to subscriber, redrawn as the graph changes.

It shows itself in a window when there is a display, on the terminal otherwise; with
`--output graph.svg` (or `.dot`) it writes the graph once and exits, and with neither a
display nor a terminal it prints the DOT text. Its own node is hidden.
"""

from __future__ import annotations

import argparse
import os
import sys
from typing import TYPE_CHECKING

from ros2lite.demos.display import DisplayError, add_display_argument, choose, own_arguments
from ros2lite.demos.rqt_graph import model
from ros2lite.demos.runner import run_main

if TYPE_CHECKING:
    from ros2lite.node import Node

REFRESH_SECONDS = 1.0
OUTPUTS = ('.svg', '.dot', '.gv')


def write_output(path: str, graph: model.Graph) -> None:
    """The graph as SVG or DOT, by the file's extension; never through a symlink."""
    from ros2lite.demos.rqt_graph.output import to_dot, to_svg

    ext = os.path.splitext(path)[1].lower()
    if ext not in OUTPUTS:
        raise ValueError(f"cannot write '{path}': the name must end in .svg or .dot")
    text = to_svg(graph) if ext == '.svg' else to_dot(graph)
    flags = os.O_WRONLY | os.O_CREAT | os.O_TRUNC | getattr(os, 'O_NOFOLLOW', 0)
    try:
        fd = os.open(path, flags, 0o644)
    except OSError as e:
        raise ValueError(f"cannot write '{path}': {e.strerror}") from None
    with os.fdopen(fd, 'w', encoding='utf-8') as f:
        f.write(text)


def graph_node() -> Node:
    """The hidden node the graph is read through."""
    from ros2lite.node import Node

    return Node(
        f'_ros2lite_rqt_graph_{os.getpid()}', enable_rosout=False, start_parameter_services=False
    )


def run(options: argparse.Namespace) -> None:
    """Show the live graph (or write it to a file) as the options say."""
    node = graph_node()
    filters = model.Options(
        include_hidden=options.include_hidden,
        show_debug=options.show_debug,
        show_leaf_topics=options.show_leaf_topics,
    )

    def current() -> model.Graph:
        # one complete liveliness query per picture: a graph cache that has just started
        # may not have heard every token yet
        from ros2lite.graph import snapshot

        context = node.context
        return model.from_entities(snapshot(context.require(), context.domain_id), filters)

    if options.output:
        write_output(options.output, current())
        return
    for kind in choose(options.display):
        try:
            if kind == 'window':
                from ros2lite.demos.rqt_graph.window_view import GraphWindow

                GraphWindow().run(current, node.context.ok, REFRESH_SECONDS)
                return
            if kind == 'terminal':
                from ros2lite.demos.rqt_graph.terminal_view import GraphTerminal

                GraphTerminal().run(current, node.context.ok, REFRESH_SECONDS)
                return
        except DisplayError:
            if options.display != 'auto':
                raise
            continue
        from ros2lite.demos.rqt_graph.output import to_dot

        sys.stdout.write(to_dot(current()))
        return


def main(args: list[str] | None = None) -> int:
    """`rqt_graph`'s entry point."""
    parser = argparse.ArgumentParser(
        prog='rqt_graph', description='Show the ROS graph: nodes, topics and who talks to whom.'
    )
    add_display_argument(parser)
    parser.add_argument(
        '-o', '--output', metavar='FILE', help='write the graph to FILE (.svg or .dot) and exit'
    )
    parser.add_argument(
        '--include-hidden', action='store_true', help='show hidden nodes and topics too'
    )
    parser.add_argument(
        '--show-debug', action='store_true', help='show /rosout and /parameter_events'
    )
    parser.add_argument(
        '--show-leaf-topics',
        action='store_true',
        help='show topics that have no publisher or no subscriber',
    )
    options = parser.parse_args(own_arguments(args))
    return run_main(lambda: run(options), args)


if __name__ == '__main__':
    sys.exit(main())
