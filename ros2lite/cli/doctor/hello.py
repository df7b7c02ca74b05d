"""`doctor hello`: can this host and others talk? A hello goes out every emit period on a
topic and to the multicast group; every print period a table says how many went out and
how many arrived from each other host, by topic and by multicast.

ros2lite adds `--group/--port/--interface` (as `multicast send|receive` have them) and takes
`--ttl 0`, which keeps the multicast part on this machine.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import click

from ..multicast.common import address_options
from ..parsing import command

if TYPE_CHECKING:
    from ros2lite.tools.hello import HelloCounts

POSITIVE = click.FloatRange(min=0, min_open=True)


@command('hello')
@click.option(
    '-t',
    '--topic',
    default='/canyouhearme',
    help="Name of ROS topic to publish to (default: '/canyouhearme')",
)
@click.option(
    '-ep',
    '--emit-period',
    metavar='N',
    type=POSITIVE,
    default=0.1,
    help='Time period to publish/send one message (default: 0.1s)',
)
@click.option(
    '-pp',
    '--print-period',
    metavar='N',
    type=POSITIVE,
    default=1.0,
    help='Time period to print summary table (default: 1.0s)',
)
@click.option(
    '--ttl',
    type=click.IntRange(0, 255),
    help='TTL for multicast send (default: None; 0 keeps it on this host)',
)
@click.option(
    '-1',
    '--once',
    is_flag=True,
    help='Publish and multicast send for one emit period then exit; used in test case.',
)
@address_options
def cli(
    topic: str,
    emit_period: float,
    print_period: float,
    ttl: int | None,
    once: bool,
    group: str,
    port: int,
    interface: str | None,
) -> None:
    """Check network connectivity between multiple hosts.

    Run it on each host: it publishes and multicasts hellos and counts those of the other
    hosts (the topic part goes through the Zenoh router, the multicast part does not).
    """
    from ros2lite.tools.hello import Hello, hello_node_name
    from ros2lite.tools.multicast import check_settings

    from ..common import connect

    check_settings(group, port, interface, ttl)

    def summary() -> None:
        _print_summary(hello.take_counts(), topic, print_period, group, port)

    with connect() as conn:
        hello = Hello(
            conn.node(hello_node_name()),
            topic,
            group=group,
            port=port,
            ttl=ttl,
            interface=interface,
        )
        try:
            if once:
                hello.emit()
                conn.spin_until(timeout=emit_period)
                summary()
                return
            conn.every(print_period, summary)
            conn.every(emit_period, hello.emit)
            hello.emit()
            conn.spin()
        except KeyboardInterrupt:
            pass  # ros2doctor's way out: status 0
        finally:
            hello.close()


def _print_summary(
    counts: HelloCounts, topic: str, print_period: float, group: str, port: int
) -> None:
    """ros2doctor's table, column for column."""

    def table(rows: dict[str, int]) -> None:
        click.echo('{:<15} {:<20} {:<10}'.format('', 'Hostname', f'Msg Count /{print_period}s'))
        for host, count in rows.items():
            click.echo('{:<15} {:<20} {:<10}'.format('', host, count))

    click.echo('MULTIMACHINE COMMUNICATION SUMMARY')
    click.echo(f'Topic: {topic}, Published Msg Count: {counts.published}')
    click.echo('Subscribed from:')
    table(counts.subscribed)
    click.echo(f'Multicast Group/Port: {group}/{port}, Sent Msg Count: {counts.sent}')
    click.echo('Received from:')
    table(counts.received)
    click.echo('-' * 60)
