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
from typing import TYPE_CHECKING

from ros2lite.bundled.display import DisplayError, add_display_argument, choose, own_arguments
from ros2lite.monitor.plot import DEFAULT_WINDOW, Plot, PlotError, subscribe

if TYPE_CHECKING:
    from ros2lite.monitor.topic import TopicMonitor
    from ros2lite.node import Node
    from ros2lite.qos import QoSProfile

PERIOD = 0.1  # s between redraws: a sample shows well within a second
PRINT_PERIOD = 1.0  # s between text pictures without a display


def show(session: Session, display: str, window: float, ok: Callable[[], bool]) -> None:
    """Show the session's plot where `display` says (see ros2lite.bundled.display) while
    `ok()`."""
    plot = session.plot
    for kind in choose(display):
        try:
            if kind == 'window':
                from ros2lite.bundled.rqt_plot.window_view import PlotWindow

                PlotWindow(plot, window, add=session.add).run(ok, PERIOD)
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


class Session:
    """The node's side of a running rqt_plot: its monitors and subscriptions, and adding a
    series while it runs (the window's topic box)."""

    def __init__(self, node: Node, plot: Plot) -> None:
        self.node = node
        self.plot = plot
        self.monitors: dict[str, TopicMonitor] = {}
        self.types: dict[str, str] = {}

    def qos(self, watch: TopicMonitor) -> QoSProfile:
        from ros2lite.qos import qos_profile_sensor_data

        return watch.matched_qos(qos_profile_sensor_data).profile

    def watch(self, topic: str, wait: bool) -> None:
        """A monitor of `topic` and its type (waited for, or PlotError when not yet known)."""
        from ros2lite.monitor.topic import TopicMonitor

        if topic in self.monitors:
            return
        monitor = TopicMonitor(self.node, topic, self.node.context.graph.entities)
        type_name = monitor.wait_for_type() if wait else monitor.graph_type()
        if type_name is None:
            raise PlotError(f"'{topic}' has no type in the graph yet")
        self.monitors[topic], self.types[topic] = monitor, type_name

    def start(self) -> None:
        """Subscribe to every topic the plot has."""
        for topic in self.plot.topics:
            self.watch(topic, wait=True)
        subscribe(self.plot, self.monitors, self.types, self.qos)

    def add(self, text: str) -> str | None:
        """Plot `text` (``/turtle1/pose/theta``) too; why not, in one line, if it cannot be."""
        from ros2lite.interfaces import get_interface
        from ros2lite.monitor.plot import resolve_specs
        from ros2lite.monitor.topic import MultipleTypesError

        text = text.strip()
        if not text:
            return None
        text = text if text.startswith('/') else '/' + text
        try:
            specs = resolve_specs([text], self._topic_names, timeout=0)
            new_topics = sorted({s.topic for s in specs} - set(self.plot.topics))
            for spec in specs:
                self.watch(spec.topic, wait=False)
                if spec.check(get_interface(self.types[spec.topic])) != 'number':
                    raise PlotError(f"'{spec.label}' is an array; name an element ([0]) of it")
            self.plot.add(specs)
            subscribe(self.plot, self.monitors, self.types, self.qos, topics=new_topics)
        except (PlotError, MultipleTypesError) as e:
            return str(e)
        return None

    def _topic_names(self) -> list[str]:
        return [name for name, _ in self.node.get_topic_names_and_types()]


def run(texts: list[str], display: str, window: float) -> None:
    """Subscribe a node of our own (named as rqt's node is) to the series and show them."""
    from ros2lite.bundled.runner import rqt_node_name
    from ros2lite.bundled.teleop.spinning import BackgroundSpin
    from ros2lite.monitor.plot import resolve_specs
    from ros2lite.node import Node

    node = Node(rqt_node_name())
    log = node.get_logger()
    try:
        with BackgroundSpin(node):
            specs = resolve_specs(
                texts,
                lambda: [name for name, _ in node.get_topic_names_and_types()],
                lambda text: log.warn(f"no topic for '{text}' is published yet: waiting"),
            )
            session = Session(node, Plot(specs, window=window))
            session.start()
            show(session, display, window, node.context.ok)
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
        nargs='*',
        metavar='TOPIC/FIELD',
        help='what to plot, e.g. /turtle1/pose/x, /turtle1/pose/x:y, /scan/ranges[0] (in a '
        'window, more can be added in its topic box)',
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
    if not options.topics and choose(options.display)[0] != 'window':
        parser.error('name what to plot (TOPIC/FIELD …): only a window has a box to add it in')
    texts = [t if t.startswith('/') else '/' + t for t in options.topics]
    return run_main(lambda: run(texts, options.display, options.time_window), args)


if __name__ == '__main__':
    sys.exit(main())
