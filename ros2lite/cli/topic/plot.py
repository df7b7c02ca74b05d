"""`topic plot`: live lines of numbers from topics, drawn in braille in any terminal (SSH,
tmux), or written as a PNG/SVG picture or CSV rows; a verb ros2cli lacks (ros2/ros2cli#1189).

Fields are named as rqt_plot names them (``/turtle1/pose/x``, ``/scan/ranges[0]``); the
subscription QoS is matched to the publishers, so sensor-data topics plot too.
"""

from __future__ import annotations

import sys
from typing import TYPE_CHECKING

import click

from .. import completion, numbers
from ..common import connect, plot_request
from ..errors import CliError
from ..options import plot_options, qos_options, strategy_options
from ..parsing import command
from ..render import PlotScreen, fancy, print_chart, write_plot
from .common import choose_qos, graph_type, monitor, warn_type_mismatch

CSV_PERIOD = 0.05  # s between writes of the CSV rows that came

if TYPE_CHECKING:
    from typing_extensions import Unpack

    from ros2lite.monitor.plot import Plot
    from ros2lite.monitor.topic import TopicMonitor
    from ros2lite.qos import QoSProfile
    from ros2lite.tools.connection import Connection

    from ..options import QosOptions


@command('plot')
@click.argument(
    'series', nargs=-1, required=True, metavar='TOPIC/FIELD...', shell_complete=completion.topics
)
@strategy_options()
@qos_options('sensor_data')
@plot_options(live=True)
@click.option(
    '--time-window',
    type=numbers.seconds(min_open=True),
    default=10.0,
    show_default=True,
    metavar='SECONDS',
    help='How many seconds of samples the terminal shows (the x axis scrolls)',
)
@click.option(
    '--duration',
    type=numbers.seconds(min_open=True),
    metavar='SECONDS',
    help='Stop after SECONDS (and write the picture, if asked for one)',
)
@click.option(
    '--count',
    type=numbers.Count(min=1),
    metavar='N',
    help='Stop after N messages (a --snapshot picture: after the first)',
)
@click.option(
    '--redraw',
    type=numbers.rate(),
    default=10.0,
    show_default=True,
    metavar='HZ',
    help='Redraws per second on the terminal',
)
def cli(
    series: tuple[str, ...],
    xy: bool,
    snapshot: bool,
    header_stamp: bool,
    png_path: str | None,
    svg_path: str | None,
    csv_out: bool,
    size: tuple[int, int],
    time_window: float,
    duration: float | None,
    count: int | None,
    redraw: float,
    use_sim_time: bool,
    no_daemon: bool,
    **qos: Unpack[QosOptions],
) -> None:
    """Plot numeric fields of topics live (TOPIC/FIELD as rqt_plot takes them)."""
    from ros2lite.graph import topic_names_and_types
    from ros2lite.monitor.plot import Plot, PlotError, resolve_specs, subscribe

    texts, pictures = plot_request(series, xy, snapshot, (png_path, svg_path), csv_out)
    if snapshot and count is None and pictures:
        count = 1  # a picture of a profile: the first one that comes
    live = not pictures and not csv_out and fancy()
    rows: list[list[str]] | None = [] if csv_out else None
    with connect(no_daemon=no_daemon, use_sim_time=use_sim_time) as conn:
        try:
            specs = resolve_specs(
                texts,
                lambda: [name for name, _ in topic_names_and_types(conn.entities())],
                lambda text: click.echo(
                    f'WARNING: no topic for [{text}] appears to be published yet', err=True
                ),
                timeout=duration,
            )
            plot = Plot(
                specs,
                mode='xy' if xy else 'snapshot' if snapshot else 'time',
                window=time_window if live else None,
                header_stamp=header_stamp,
                rows=rows,
            )
            plot.limit = count
            monitors, types = watch_topics(conn, plot)
            if rows is not None:
                click.echo(','.join(plot.csv_header()))
            executor = conn.executor
            if rows is not None:
                csv_rows = rows
                conn.every(CSV_PERIOD, lambda: print_rows(csv_rows))
            if count is not None:
                # on a receive thread: only the spinning thread's wake-up for the end
                plot.on_sample = lambda: executor.wake() if plot.messages >= count else None
            subscribe(plot, monitors, types, lambda watch: matched_qos(watch, qos))
        except PlotError as e:
            raise CliError(str(e)) from None
        if live:
            screen = PlotScreen()
            conn.every(1.0 / redraw, lambda: screen.show(plot, time_window))
            try:
                spin(conn, plot, duration, count)
            finally:
                screen.close(plot, time_window)
            return
        try:
            spin(conn, plot, duration, count)
        finally:
            if pictures:
                write_plot(plot, pictures, size)
            elif rows is not None:
                print_rows(rows)
            else:
                print_chart(plot, None)


def spin(conn: Connection, plot: Plot, duration: float | None, count: int | None) -> None:
    """Run until `duration` s pass, `count` messages came, or Ctrl-C."""
    done = (lambda: plot.messages >= count) if count is not None else None
    conn.spin_until(done, duration)


def print_rows(rows: list[list[str]]) -> None:
    """Print (and forget) the CSV rows that came since the last call (the receive threads
    append to the list; this, on the executor, takes from its front)."""
    out = sys.stdout
    taken = len(rows)
    for row in rows[:taken]:
        out.write(','.join(row) + '\n')
    del rows[:taken]
    out.flush()


def watch_topics(conn: Connection, plot: Plot) -> tuple[dict[str, TopicMonitor], dict[str, str]]:
    """A monitor and the graph's type for each topic of `plot`."""
    monitors: dict[str, TopicMonitor] = {}
    types: dict[str, str] = {}
    for topic in plot.topics:
        watch = monitor(conn, topic)
        type_name = graph_type(watch, wait=True)
        assert type_name is not None
        warn_type_mismatch(watch, type_name)
        monitors[topic], types[topic] = watch, type_name
    return monitors, types


def matched_qos(watch: TopicMonitor, options: QosOptions) -> QoSProfile:
    """The subscription QoS: the options' profile matched to the topic's publishers."""
    return choose_qos(watch, options, err=True)
