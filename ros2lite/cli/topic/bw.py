"""`topic bw`: bandwidth of a topic, from the sizes of raw (never decoded) samples."""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import TYPE_CHECKING

import click

from .. import completion, render
from ..common import connect
from ..options import NDJSON, json_option, strategy_options
from ..parsing import command
from .common import watch, window_option

if TYPE_CHECKING:
    from ros2lite.monitor.stats import BandwidthSummary

DEFAULT_WINDOW_SIZE = 100


def _scaled(bytes_per_s: float) -> Callable[[float], str]:
    """ros2cli picks one unit (base 1000) from the rate and uses it for every number."""
    if bytes_per_s < 1000:
        return lambda n: f'{n:.0f} B'
    if bytes_per_s < 1000_000:
        return lambda n: f'{n / 1000:.2f} KB'
    return lambda n: f'{n / 1000 / 1000:.2f} MB'


def bw_line(s: BandwidthSummary) -> str:
    """ros2cli's two lines: the rate, then the message sizes."""
    fmt = _scaled(s.bytes_per_second)
    return (
        f'{fmt(s.bytes_per_second)}/s from {s.count} messages\n'
        f'\tMessage size mean: {fmt(s.mean)} min: {fmt(s.min)} max: {fmt(s.max)}'
    )


@command('bw')
@click.argument('topic', shell_complete=completion.topics)
@window_option(DEFAULT_WINDOW_SIZE, 'maximum window')
@strategy_options(no_daemon=False)
@json_option(
    f'{NDJSON}: {{"topic", "bytes_per_second", "count", "mean", "min", "max"}} per report '
    '(sizes in bytes)'
)
def cli(topic: str, window: int, use_sim_time: bool, as_json: bool) -> None:
    """Display bandwidth used by topic."""
    from ros2lite.monitor.stats import BandwidthStats
    from ros2lite.qos import qos_profile_sensor_data

    stats = BandwidthStats(window)
    with connect(use_sim_time=use_sim_time) as conn:
        watched, type_name = watch(conn, topic)
        clock = conn.node().get_clock()

        def now_ns() -> int:
            t: int = clock.now().nanoseconds if use_sim_time else time.time_ns()
            return t

        def on_arrival(size: int, _attachment: bytes, arrived: int) -> None:
            stats.add(now_ns() if use_sim_time else arrived, size)

        def report() -> None:
            summary = stats.summary(now_ns())
            if summary is not None and as_json:
                render.print_json_line(
                    {
                        'topic': topic,
                        'bytes_per_second': summary.bytes_per_second,
                        'count': summary.count,
                        'mean': summary.mean,
                        'min': summary.min,
                        'max': summary.max,
                    }
                )
            elif summary is not None:
                click.echo(bw_line(summary))

        # sizes are taken as samples arrive, so none is missed and none is decoded
        watched.on_arrival(type_name, qos_profile_sensor_data, on_arrival)
        click.echo(f'Subscribed to [{topic}]', err=as_json)
        conn.node().create_timer(1.0, report)
        conn.spin()
