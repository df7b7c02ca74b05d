"""`topic hz`: receive rate of one or more topics, counted on raw samples.

Samples are never decoded unless `--filter` needs the message: each one only adds its arrival
time, taken on the Zenoh thread as it comes in (`TopicMonitor.on_arrival`), to a
`monitor.stats.RateStats`. Nothing is queued, so a busy consumer can neither delay the stamps
nor drop samples, and the rate stays exact at 10 kHz.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

import click

from .. import completion, render
from ..common import connect
from ..options import NDJSON, json_option, strategy_options
from ..parsing import command
from .common import compile_filter, watch, window_option

if TYPE_CHECKING:
    from ros2lite.monitor.stats import IntervalSummary, RateStats
    from ros2lite.monitor.topic import TopicMonitor
    from ros2lite.node import Node
    from ros2lite.subscription import MessageInfo

DEFAULT_WINDOW_SIZE = 10000
HEADER = ['topic', 'rate', 'min_delta', 'max_delta', 'std_dev', 'window']


def hz_line(s: IntervalSummary) -> str:
    """ros2cli's two lines for one topic."""
    return (
        f'average rate: {s.rate:.3f}\n\tmin: {s.min * 1e-9:.3f}s '
        f'max: {s.max * 1e-9:.3f}s std dev: {s.std_dev * 1e-9:.5f}s window: {s.count}'
    )


def table_cells(topic: str, s: IntervalSummary) -> list[str]:
    """One row of ros2cli's table for several topics."""
    return [
        topic,
        f'{s.rate:.3f}',
        f'{s.min * 1e-9:.3f}',
        f'{s.max * 1e-9:.3f}',
        f'{s.std_dev * 1e-9:.5f}',
        str(s.count),
    ]


def ros_or_arrival_time(node: Node, wall_time: bool) -> Callable[[int], int]:
    """When a sample counts as received, given its arrival time: that time itself (wall
    clock, which is ROS time too unless sim time is on), or the node's sim time."""
    clock = node.get_clock()
    if wall_time:
        return lambda arrived: arrived

    def ros_time(arrived: int) -> int:
        if clock.ros_time_is_active:
            now: int = clock.now().nanoseconds
            return now
        return arrived

    return ros_time


@command('hz')
@click.argument(
    'topic_names',
    metavar='TOPIC_NAME...',
    nargs=-1,
    required=True,
    shell_complete=completion.topics,
)
@window_option(DEFAULT_WINDOW_SIZE, 'window')
@click.option(
    '--filter',
    'filter_expr',
    metavar='EXPR',
    help='only measure messages matching the specified Python expression',
)
@click.option(
    '--wall-time',
    is_flag=True,
    help='calculates rate using wall time which can be helpful when clock is not '
    'published during simulation',
)
@strategy_options(no_daemon=False)
@json_option(
    f'{NDJSON}: {{"topic", "rate", "min", "max", "std_dev", "window"}} per topic and report '
    '(Hz; seconds)'
)
def cli(
    topic_names: tuple[str, ...],
    window: int,
    filter_expr: str | None,
    wall_time: bool,
    use_sim_time: bool,
    as_json: bool,
) -> None:
    """Print the average publishing rate to screen

    The rate is measured where the subscription receives samples, so it can differ from the
    publisher's rate when resources or QoS get in the way.
    """
    from ros2lite.monitor.stats import RateStats

    filter_fn = compile_filter(filter_expr)
    with connect(use_sim_time=use_sim_time) as conn:
        stamp = ros_or_arrival_time(conn.node(), wall_time)
        stats: dict[str, RateStats] = {}
        # Ctrl-C, hz's usual end, leaves with status 2 as in every other verb (ros2cli's)
        for topic in topic_names:
            watched, type_name = watch(conn, topic)
            stats[topic] = rate = RateStats(window)
            _subscribe(watched, type_name, rate, stamp, filter_fn, as_json)
            if len(topic_names) > 1:
                click.echo(f'Subscribed to [{topic}]', err=as_json)
        report = _Report(stats, as_json)
        try:
            conn.every(1.0, report)
            conn.spin()
        finally:
            report.close()


def _subscribe(
    watched: TopicMonitor,
    type_name: str,
    rate: RateStats,
    stamp: Callable[[int], int],
    filter_fn: Callable[[object], object] | None,
    as_json: bool = False,
) -> None:
    """Count samples on arrival (Zenoh thread, nothing queued or decoded) unless a filter
    needs the message; then decode on the executor and use the arrival stamp it carries."""
    from ros2lite.qos import qos_profile_sensor_data

    def record(arrived: int) -> None:
        if rate.add(stamp(arrived)):
            click.echo('time has reset, resetting counters', err=as_json)

    if filter_fn is None:
        watched.on_arrival(
            type_name, qos_profile_sensor_data, lambda _size, _att, arrived: record(arrived)
        )
        return
    from ros2lite.interfaces import deserialize

    def count_matching(data: bytes, info: MessageInfo) -> None:
        if filter_fn(deserialize(type_name, data)):
            record(info.received_timestamp)

    watched.on_sample(type_name, qos_profile_sensor_data, count_matching)


class _Report:
    """Once a second: one topic's summary line, or a table of several (live on a terminal)."""

    def __init__(self, stats: dict[str, RateStats], as_json: bool = False) -> None:
        self.stats = stats
        self.as_json = as_json
        fancy = len(stats) > 1 and render.fancy() and not as_json
        self.live = render.LiveTable(HEADER) if fancy else None

    def __call__(self) -> None:
        if self.as_json:
            for topic, rate in self.stats.items():
                s = rate.summary()
                if s is not None:
                    render.print_json_line(
                        {
                            'topic': topic,
                            'rate': s.rate,
                            'min': s.min * 1e-9,
                            'max': s.max * 1e-9,
                            'std_dev': s.std_dev * 1e-9,
                            'window': s.count,
                        }
                    )
            return
        if len(self.stats) == 1:
            summary = next(iter(self.stats.values())).summary()
            if summary is not None:
                click.echo(hz_line(summary))
            return
        rows = []
        for topic, rate in self.stats.items():
            summary = rate.summary()
            if summary is not None:
                rows.append(table_cells(topic, summary))
        if not rows:
            return
        if self.live is not None:
            self.live.show(rows)
        else:
            click.echo(render.ascii_table(HEADER, rows))

    def close(self) -> None:
        if self.live is not None:
            self.live.close()
