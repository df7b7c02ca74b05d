"""`topic delay`: how old messages are on arrival, from the stamp in their header."""

from __future__ import annotations

from typing import TYPE_CHECKING, Protocol, cast

import click

from .. import completion, render
from ..common import connect
from ..errors import CliError
from ..options import NDJSON, json_option, strategy_options
from ..parsing import command
from .common import watch, window_option

if TYPE_CHECKING:
    from ros2lite.monitor.stats import IntervalSummary
    from ros2lite.msgs.std_msgs.msg import Header
    from ros2lite.subscription import MessageInfo


class _Stamped(Protocol):
    """A message with a std_msgs/Header (the type is checked to have one)."""

    header: Header


DEFAULT_WINDOW_SIZE = 10000


def delay_line(s: IntervalSummary) -> str:
    """ros2cli's two lines for the delays in the window."""
    return (
        f'average delay: {s.mean * 1e-9:.3f}\n\tmin: {s.min * 1e-9:.3f}s '
        f'max: {s.max * 1e-9:.3f}s std dev: {s.std_dev * 1e-9:.5f}s window: {s.count}'
    )


@command('delay')
@click.argument('topic', shell_complete=completion.topics)
@window_option(DEFAULT_WINDOW_SIZE, 'window', minimum=0)
@strategy_options(no_daemon=False)
@json_option(
    f'{NDJSON}: {{"topic", "mean", "min", "max", "std_dev", "window"}} per report (seconds; '
    '{"topic", "window": 0} when no new message came)'
)
def cli(topic: str, window: int, use_sim_time: bool, as_json: bool) -> None:
    """Display delay of topic from timestamp in header."""
    from ros2lite.interfaces import deserialize, get_interface
    from ros2lite.monitor.stats import DelayStats
    from ros2lite.qos import qos_profile_sensor_data

    stats = DelayStats(window)
    with connect(use_sim_time=use_sim_time) as conn:
        watched, type_name = watch(conn, topic)
        if 'header' not in get_interface(type_name).get_fields_and_field_types():
            raise CliError('msg does not have header')
        clock = conn.node().get_clock()

        def on_sample(data: bytes, info: MessageInfo) -> None:
            stamp = cast(_Stamped, deserialize(type_name, data)).header.stamp
            now = clock.now().nanoseconds if clock.ros_time_is_active else info.received_timestamp
            if stats.add(now, stamp.sec * 1_000_000_000 + stamp.nanosec):
                click.echo('time has reset, resetting counters', err=as_json)

        def report() -> None:
            if stats.empty:
                return
            summary = stats.summary()
            if as_json:
                render.print_json_line(
                    {'topic': topic, 'window': 0}
                    if summary is None
                    else {
                        'topic': topic,
                        'mean': summary.mean * 1e-9,
                        'min': summary.min * 1e-9,
                        'max': summary.max * 1e-9,
                        'std_dev': summary.std_dev * 1e-9,
                        'window': summary.count,
                    }
                )
                return
            click.echo('no new messages' if summary is None else delay_line(summary))

        watched.on_sample(type_name, qos_profile_sensor_data, on_sample)
        conn.node().create_timer(1.0, report)
        conn.spin()
