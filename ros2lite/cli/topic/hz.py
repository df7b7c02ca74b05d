"""`topic hz`: receive rate of one or more topics, counted on raw samples.

Samples are never decoded unless `--filter` needs the message: each one only adds its arrival
time, taken on the Zenoh thread as it comes in (`topic_monitor.MonitoredSubscription`), to a
`topic_stats.RateStats`. Nothing is queued, so a busy consumer can neither delay the stamps
nor drop samples, and the rate stays exact at 10 kHz.
"""

from __future__ import annotations

import os
import sys
import time
from collections.abc import Callable
from typing import Any

import click

from .. import completion
from ..common import CliSession, strategy_options
from .echo import compile_filter, resolve_topic, wait_for_type

DEFAULT_WINDOW_SIZE = 10000
HEADER = ['topic', 'rate', 'min_delta', 'max_delta', 'std_dev', 'window']


def hz_line(s: Any) -> str:
    return (
        f'average rate: {s.rate:.3f}\n\tmin: {s.min * 1e-9:.3f}s '
        f'max: {s.max * 1e-9:.3f}s std dev: {s.std_dev * 1e-9:.5f}s window: {s.count}'
    )


def table_cells(topic: str, s: Any) -> list[str]:
    return [
        topic,
        f'{s.rate:.3f}',
        f'{s.min * 1e-9:.3f}',
        f'{s.max * 1e-9:.3f}',
        f'{s.std_dev * 1e-9:.5f}',
        str(s.count),
    ]


def ascii_table(rows: list[list[str]]) -> str:
    """ros2cli's table: centred headers, left-justified cells, 3-space gaps, '=' rule."""
    widths = [max(len(h), *(len(r[i]) for r in rows)) for i, h in enumerate(HEADER)]
    head = '   '.join(h.center(w) for h, w in zip(HEADER, widths, strict=True))
    rule = '=' * (sum(widths) + 3 * (len(widths) - 1))
    body = '\n'.join('   '.join(c.ljust(w) for c, w in zip(r, widths, strict=True)) for r in rows)
    return f'{head}\n{rule}\n{body}\n'


class RichTable:
    """The multi-topic table as a live rich table (terminal only, colour allowed)."""

    def __init__(self) -> None:
        from rich.live import Live

        self._rows: dict[str, list[str]] = {}
        self._live = Live(auto_refresh=False, transient=False)
        self._live.start()

    def show(self, rows: list[list[str]]) -> None:
        from rich.table import Table

        for row in rows:
            self._rows[row[0]] = row
        table = Table(*HEADER)
        for row in self._rows.values():
            table.add_row(*row)
        self._live.update(table, refresh=True)

    def close(self) -> None:
        self._live.stop()


def use_rich() -> bool:
    return sys.stdout.isatty() and 'NO_COLOR' not in os.environ


def ros_or_arrival_time(node: Any, wall_time: bool) -> Callable[[int], int]:
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


@click.command('hz')
@click.argument(
    'topic_names',
    metavar='TOPIC_NAME...',
    nargs=-1,
    required=True,
    shell_complete=completion.topics,
)
@click.option(
    '-w',
    '--window',
    'window_size',
    type=click.IntRange(min=1),
    default=DEFAULT_WINDOW_SIZE,
    show_default=True,
    metavar='WINDOW',
    help='window size, in # of messages, for calculating rate',
)
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
def cli(
    topic_names: tuple[str, ...],
    window_size: int,
    filter_expr: str | None,
    wall_time: bool,
    use_sim_time: bool,
) -> None:
    """Print the average receiving rate to screen.

    The rate is measured where the subscription receives samples, so it can differ from the
    publisher's rate when resources or QoS get in the way.
    """
    from ros2lite.topic_stats import RateStats

    filter_fn = compile_filter(filter_expr)
    with CliSession(use_sim_time=use_sim_time) as session:
        node = session.node()
        stamp = ros_or_arrival_time(node, wall_time)
        stats: dict[str, RateStats] = {}
        # Ctrl-C, hz's usual end, leaves with status 2 as in every other verb (ros2cli's)
        for topic in topic_names:
            full_name = resolve_topic(node, topic)
            type_name = wait_for_type(session, topic, full_name)
            stats[topic] = rate = RateStats(window_size)
            _subscribe(node, type_name, full_name, rate, stamp, filter_fn)
            if len(topic_names) > 1:
                click.echo(f'Subscribed to [{topic}]')
        _report_every_second(session, node, stats)


def _subscribe(
    node: Any,
    type_name: str,
    topic: str,
    rate: Any,
    stamp: Callable[[int], int],
    filter_fn: Callable[[Any], Any] | None,
) -> None:
    """Count samples on arrival (Zenoh thread, nothing queued or decoded) unless a filter
    needs the message; then decode on the executor and use the arrival stamp it carries."""
    from ros2lite.qos import qos_profile_sensor_data

    def record(arrived: int) -> None:
        if rate.add(stamp(arrived)):
            click.echo('time has reset, resetting counters')

    if filter_fn is None:
        from ros2lite.topic_monitor import MonitoredSubscription

        MonitoredSubscription(
            node,
            type_name,
            topic,
            None,
            qos_profile_sensor_data,
            on_arrival=lambda _size, _att, arrived: record(arrived),
        )
        return
    from ros2lite.interfaces import deserialize

    def count_matching(data: bytes, info: Any) -> None:
        if filter_fn(deserialize(type_name, data)):
            record(info.received_timestamp)

    node.create_subscription(type_name, topic, count_matching, qos_profile_sensor_data, raw=True)


def _report_every_second(session: CliSession, node: Any, stats: dict[str, Any]) -> None:
    from ros2lite.executors import SingleThreadedExecutor

    executor = SingleThreadedExecutor(context=session.context)
    executor.add_node(node)
    fancy = RichTable() if len(stats) > 1 and use_rich() else None
    try:
        next_report = time.monotonic() + 1.0
        while session.context.ok():
            remaining = next_report - time.monotonic()
            if remaining > 0:
                executor.spin_once(remaining)
                continue
            next_report = max(next_report + 1.0, time.monotonic() + 0.5)
            if len(stats) == 1:
                summary = next(iter(stats.values())).summary()
                if summary is not None:
                    click.echo(hz_line(summary))
                continue
            rows = []
            for topic, rate in stats.items():
                summary = rate.summary()
                if summary is not None:
                    rows.append(table_cells(topic, summary))
            if not rows:
                continue
            if fancy is not None:
                fancy.show(rows)
            else:
                click.echo(ascii_table(rows))
    finally:
        if fancy is not None:
            fancy.close()
