"""`rqt_graph`: the live ROS graph, nodes as ellipses and topics as boxes, arrows from
publisher to topic to subscriber, redrawn as the graph changes.

It shows itself in a window when there is a display, on the terminal otherwise; with
`--output graph.svg` (or `.dot`) it writes the graph once and exits, and with neither a
display nor a terminal it prints the DOT text.
"""

from __future__ import annotations

import argparse
import os
import sys
from collections.abc import Callable

from ros2lite.bundled.display import DisplayError, add_display_argument, choose, own_arguments
from ros2lite.bundled.rqt_graph import model
from ros2lite.exceptions import Ros2liteError

REFRESH_SECONDS = 1.0
OUTPUTS = ('.svg', '.dot', '.gv')


def write_output(path: str, graph: model.Graph) -> None:
    """The graph as SVG or DOT, by the file's extension; never through a symlink."""
    from ros2lite.bundled.rqt_graph.output import to_dot, to_svg

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


def run(options: argparse.Namespace) -> None:
    """Show the live graph (or write it to a file) as the options say."""
    from ros2lite.tools.connection import Connection

    filters = model.Options(
        include_hidden=options.include_hidden,
        show_debug=options.show_debug,
        show_leaf_topics=options.show_leaf_topics,
    )
    # a tool's connection: every picture is the daemon's graph cache or one complete
    # liveliness query (a node's fresh peer session or graph cache may still be joining the
    # graph); a live view keeps the session open for as long as it runs, so Ctrl-C ends both
    with Connection() as conn:
        if not options.output:
            conn.open()
        _show(options, lambda: model.from_entities(conn.entities(), filters), conn.context.ok)


def _show(
    options: argparse.Namespace, current: Callable[[], model.Graph], ok: Callable[[], bool]
) -> None:
    if options.output:
        write_output(options.output, current())
        return
    for kind in choose(options.display):
        try:
            if kind == 'window':
                from ros2lite.bundled.rqt_graph.window_view import GraphWindow

                GraphWindow().run(current, ok, REFRESH_SECONDS)
                return
            if kind == 'terminal':
                from ros2lite.bundled.rqt_graph.terminal_view import GraphTerminal

                GraphTerminal().run(current, ok, REFRESH_SECONDS)
                return
        except DisplayError:
            if options.display != 'auto':
                raise
            continue
        from ros2lite.bundled.rqt_graph.output import to_dot

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
    try:
        run(options)
    except KeyboardInterrupt:
        pass
    except (Ros2liteError, ValueError) as e:  # no router, a file that cannot be written…
        print(str(e), file=sys.stderr, flush=True)
        return 1
    return 0


if __name__ == '__main__':
    sys.exit(main())
