"""`topic delay`: how old messages are on arrival, from the stamp in their header."""

from __future__ import annotations

from typing import Any

import click

from .. import completion
from ..common import CliSession, strategy_options
from ..errors import CliError
from .echo import resolve_topic, wait_for_type

DEFAULT_WINDOW_SIZE = 10000


def delay_line(s: Any) -> str:
    return (
        f'average delay: {s.mean * 1e-9:.3f}\n\tmin: {s.min * 1e-9:.3f}s '
        f'max: {s.max * 1e-9:.3f}s std dev: {s.std_dev * 1e-9:.5f}s window: {s.count}'
    )


@click.command('delay')
@click.argument('topic', shell_complete=completion.topics)
@click.option(
    '-w',
    '--window',
    type=click.IntRange(min=0),
    default=DEFAULT_WINDOW_SIZE,
    show_default=True,
    help='window size, in # of messages, for calculating rate',
)
@strategy_options(no_daemon=False)
def cli(topic: str, window: int, use_sim_time: bool) -> None:
    """Display delay of topic from timestamp in header."""
    from ros2lite.executors import SingleThreadedExecutor
    from ros2lite.interfaces import deserialize, get_interface
    from ros2lite.qos import qos_profile_sensor_data
    from ros2lite.topic_stats import DelayStats

    stats = DelayStats(window)
    with CliSession(use_sim_time=use_sim_time) as session:
        node = session.node()
        full_name = resolve_topic(node, topic)
        type_name = wait_for_type(session, topic, full_name)
        if 'header' not in get_interface(type_name).get_fields_and_field_types():
            raise CliError('msg does not have header')
        clock = node.get_clock()

        def on_sample(data: bytes, info: Any) -> None:
            stamp = deserialize(type_name, data).header.stamp
            now = clock.now().nanoseconds if clock.ros_time_is_active else info.received_timestamp
            if stats.add(now, stamp.sec * 1_000_000_000 + stamp.nanosec):
                click.echo('time has reset, resetting counters')

        def report() -> None:
            if stats.empty:
                return
            summary = stats.summary()
            click.echo('no new messages' if summary is None else delay_line(summary))

        node.create_subscription(type_name, full_name, on_sample, qos_profile_sensor_data, raw=True)
        node.create_timer(1.0, report)
        executor = SingleThreadedExecutor(context=session.context)
        executor.add_node(node)
        executor.spin()
