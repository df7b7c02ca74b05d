"""`rqt_console`: every node's log lines (`/rosout`) as they come, in a window when there is a
display, as a table on the terminal otherwise, and printed line by line when neither is.

Filters (least severity, node, text) and the number of lines kept can be set on the command
line and changed while it runs; a pause holds the picture while messages are still kept.
"""

from __future__ import annotations

import argparse
import sys
import time
from collections.abc import Callable

from ros2lite.bundled.display import DisplayError, add_display_argument, choose, own_arguments
from ros2lite.bundled.rqt_console.model import (
    COLUMNS,
    DEFAULT_LINES,
    SEVERITIES,
    Console,
    Filters,
    cells,
    line,
    parse_severity,
    widths,
)

PERIOD = 0.05  # s between looks for new messages: a line shows well within a second


def show(console: Console, display: str, ok: Callable[[], bool]) -> None:
    """Show the console where `display` says (see ros2lite.bundled.display) while `ok()`."""
    for kind in choose(display):
        try:
            if kind == 'window':
                from ros2lite.bundled.rqt_console.window_view import ConsoleWindow

                ConsoleWindow(console).run(ok, PERIOD)
                return
            if kind == 'terminal':
                from ros2lite.bundled.rqt_console.terminal_view import ConsoleTerminal

                ConsoleTerminal(console).run(ok, PERIOD)
                return
        except DisplayError:
            if display != 'auto':
                raise
            continue
        print_lines(console, ok)
        return


def print_lines(console: Console, ok: Callable[[], bool]) -> None:
    """No display: each message that passes the filters as one plain line, as it comes."""
    printed = 0
    while ok():
        rows, _ = console.shown()
        fresh = [row for row in rows if row.number > printed]
        if fresh:
            sizes = widths(fresh, 10_000)
            sizes[COLUMNS.index('Message')] = max(len(row.message) for row in fresh)
            for row in fresh:
                print(line(cells(row), sizes).rstrip(), flush=True)
            printed = fresh[-1].number
        time.sleep(PERIOD)


def run(console: Console, display: str) -> None:
    """Listen to `/rosout` with a node of our own (named as rqt's node is) and show it."""
    from ros2lite.bundled.runner import rqt_node_name
    from ros2lite.bundled.teleop.spinning import BackgroundSpin
    from ros2lite.msgs.rcl_interfaces.msg import Log
    from ros2lite.node import Node
    from ros2lite.qos import qos_profile_rosout_default

    node = Node(rqt_node_name())
    node.create_subscription(Log, '/rosout', console.add, qos_profile_rosout_default)
    try:
        with BackgroundSpin(node):
            show(console, display, node.context.ok)
    finally:
        node.destroy_node()


def _severity(text: str) -> str:
    try:
        return parse_severity(text)
    except ValueError as e:
        raise argparse.ArgumentTypeError(str(e)) from None


def _lines(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        value = 0
    if value < 1:
        raise argparse.ArgumentTypeError(f"'{text}' is not a whole number of lines of 1 or more")
    return value


def main(args: list[str] | None = None) -> int:
    """`rqt_console`'s entry point."""
    from ros2lite.bundled.runner import run_main

    parser = argparse.ArgumentParser(
        prog='rqt_console', description='Show the log messages of every node (/rosout).'
    )
    add_display_argument(parser)
    parser.add_argument(
        '--severity',
        type=_severity,
        default='DEBUG',
        metavar='LEVEL',
        help=f'show messages of this severity or worse ({", ".join(SEVERITIES)}; default DEBUG)',
    )
    parser.add_argument('--node', default='', help='show only nodes whose name contains NODE')
    parser.add_argument(
        '--filter', default='', metavar='TEXT', help='show only messages containing TEXT'
    )
    parser.add_argument(
        '--lines',
        type=_lines,
        default=DEFAULT_LINES,
        metavar='N',
        help=f'keep the last N messages (default {DEFAULT_LINES})',
    )
    options = parser.parse_args(own_arguments(args))
    console = Console(options.lines, Filters(options.severity, options.node, options.filter))
    return run_main(lambda: run(console, options.display), args)


if __name__ == '__main__':
    sys.exit(main())
