"""`rqt_plot`: live lines of numeric fields of topics, named as rqt_plot takes them
(``/turtle1/pose/x``, ``/turtle1/pose/x:y``, ``/scan/ranges[0]``), in a window when there is
a display (legend, autoscale, pause, a scrolling time window), on the terminal otherwise, and
as one text picture a second without either.

The subscriptions match what the publishers offer (sensor-data QoS topics plot too, which
rqt_plot's own cannot); the samples live in the library's bounded series
(ros2lite.monitor.plot), the same that `ros2lite topic plot` draws.
"""

from __future__ import annotations

import argparse
import sys
import time
from collections.abc import Callable

from ros2lite.bundled.display import DisplayError, add_display_argument, choose, own_arguments
from ros2lite.monitor.plot import DEFAULT_WINDOW, Plot

PERIOD = 0.1  # s between redraws: a sample shows well within a second
PRINT_PERIOD = 1.0  # s between text pictures without a display


def show(plot: Plot, display: str, window: float, ok: Callable[[], bool]) -> None:
    """Show `plot` where `display` says (see ros2lite.bundled.display) while `ok()`."""
    for kind in choose(display):
        try:
            if kind == 'window':
                from ros2lite.bundled.rqt_plot.window_view import PlotWindow

                PlotWindow(plot, window).run(ok, PERIOD)
                return
            if kind == 'terminal':
                from ros2lite.bundled.rqt_plot.terminal_view import PlotTerminal

                PlotTerminal(plot, window).run(ok, PERIOD)
                return
        except DisplayError:
            if display != 'auto':
                raise
            continue
        print_pictures(plot, window, ok)
        return


def print_pictures(plot: Plot, window: float, ok: Callable[[], bool]) -> None:
    """No display: the plot as plain text, once a second while samples come."""
    from ros2lite.monitor.chart import braille
    from ros2lite.monitor.plot import to_chart

    shown = 0
    while ok():
        if plot.messages != shown:
            shown = plot.messages
            print(braille(to_chart(plot, window=window), 80, 20, colour=False), flush=True)
        time.sleep(PRINT_PERIOD)


def run(texts: list[str], display: str, window: float) -> None:
    """Subscribe a node of our own (named as rqt's node is) to the series and show them."""
    from ros2lite.bundled.runner import rqt_node_name
    from ros2lite.bundled.teleop.spinning import BackgroundSpin
    from ros2lite.monitor.plot import resolve_specs, subscribe
    from ros2lite.monitor.topic import TopicMonitor
    from ros2lite.node import Node
    from ros2lite.qos import qos_profile_sensor_data

    node = Node(rqt_node_name())
    log = node.get_logger()
    try:
        with BackgroundSpin(node):
            specs = resolve_specs(
                texts,
                lambda: [name for name, _ in node.get_topic_names_and_types()],
                lambda text: log.warn(f"no topic for '{text}' is published yet: waiting"),
            )
            plot = Plot(specs, window=window)
            entities = node.context.graph.entities
            monitors = {t: TopicMonitor(node, t, entities) for t in plot.topics}
            types = {t: m.wait_for_type() for t, m in monitors.items()}
            subscribe(
                plot,
                monitors,
                types,
                lambda watch: watch.matched_qos(qos_profile_sensor_data).profile,
            )
            show(plot, display, window, node.context.ok)
    finally:
        node.destroy_node()


def _seconds(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        value = 0.0
    if not 0 < value <= 86_400:
        raise argparse.ArgumentTypeError(f"'{text}' is not a number of seconds (0 to 86400)")
    return value


def main(args: list[str] | None = None) -> int:
    """`rqt_plot`'s entry point."""
    from ros2lite.bundled.runner import run_main

    parser = argparse.ArgumentParser(
        prog='rqt_plot', description='Plot numeric fields of topics as they change.'
    )
    parser.add_argument(
        'topics',
        nargs='+',
        metavar='TOPIC/FIELD',
        help='what to plot, e.g. /turtle1/pose/x, /turtle1/pose/x:y, /scan/ranges[0]',
    )
    add_display_argument(parser)
    parser.add_argument(
        '--time-window',
        type=_seconds,
        default=DEFAULT_WINDOW,
        metavar='SECONDS',
        help=f'how many seconds the x axis spans (default {DEFAULT_WINDOW:g})',
    )
    options = parser.parse_args(own_arguments(args))
    texts = [t if t.startswith('/') else '/' + t for t in options.topics]
    return run_main(lambda: run(texts, options.display, options.time_window), args)


if __name__ == '__main__':
    sys.exit(main())
