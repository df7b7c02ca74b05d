"""`topic pub`: publish a message built from YAML, once, N times or at a rate."""

from __future__ import annotations

import sys
import time
from typing import TYPE_CHECKING

import click

from .. import completion, numbers
from ..common import connect, known_type, message_fields, yaml_fields
from ..errors import CliError
from ..options import check_stdin, qos_from_options, qos_options, strategy_options, values_argument
from ..parsing import command
from .common import message_type_name

if TYPE_CHECKING:
    from typing_extensions import Unpack

    from ros2lite.qos import QoSProfile
    from ros2lite.tools.connection import Connection

    from ..options import QosOptions

WAIT_STEP = 0.1  # seconds between subscription-count checks while waiting


@command('pub')
@click.argument('topic_name', shell_complete=completion.topics)
@click.argument('message_type', shell_complete=completion.message_types)
@values_argument()
@click.option(
    '-r',
    '--rate',
    type=numbers.rate(),
    default=1.0,
    metavar='N',
    show_default=True,
    help='Publishing rate in Hz',
)
@click.option(
    '-p',
    '--print',
    'print_nth',
    type=numbers.Count(min=0),
    default=1,
    metavar='N',
    show_default=True,
    help='Only print every N-th published message (0: never)',
)
@click.option('-1', '--once', is_flag=True, help='Publish one message and exit')
@click.option(
    '-t',
    '--times',
    type=numbers.Count(min=0),
    default=0,
    show_default=True,
    help='Publish this number of times and then exit (0: forever)',
)
@click.option(
    '-w',
    '--wait-matching-subscriptions',
    type=numbers.Count(min=0),
    help='Wait until finding the specified number of matching subscriptions. '
    'Defaults to 1 when using "-1"/"--once"/"--times", otherwise to 0.',
)
@click.option(
    '--max-wait-time-secs',
    type=numbers.seconds(min_open=True),
    help='Maximum wait time in seconds for --wait-matching-subscriptions (default: wait forever)',
)
@click.option(
    '--keep-alive',
    type=numbers.seconds(min_open=True),
    default=0.1,
    metavar='N',
    show_default=True,
    help='Keep publishing node alive for N seconds after the last msg',
)
@click.option('-n', '--node-name', help='Name of the created publishing node')
@qos_options('default')
@strategy_options(no_daemon=False)
def cli(
    topic_name: str,
    message_type: str,
    values: str | None,
    use_stdin: bool,
    rate: float,
    print_nth: int,
    once: bool,
    times: int,
    wait_matching_subscriptions: int | None,
    max_wait_time_secs: float | None,
    keep_alive: float,
    node_name: str | None,
    use_sim_time: bool,
    **qos: Unpack[QosOptions],
) -> None:
    """Publish a message to a topic.

    VALUES fills the message in YAML (e.g. 'data: Hello World') or as `topic echo --json`
    prints it (base64 byte arrays, "nan"/"inf" strings); 'now' sets a time field and
    'header: auto' a header to the current time on every publish.
    """
    check_stdin(values, use_stdin)
    if once and times:
        raise click.UsageError('argument -t/--times: not allowed with argument -1/--once')
    if use_stdin:
        values = sys.stdin.read()
    if once:
        times = 1
    wait_for = (
        wait_matching_subscriptions if wait_matching_subscriptions is not None else int(times != 0)
    )
    profile = qos_from_options(**qos)
    with connect(use_sim_time=use_sim_time) as conn:
        conn.node(node_name)
        publish_loop(
            conn,
            topic_name,
            message_type,
            '{}' if values is None else values,
            1.0 / rate,
            print_nth,
            times,
            wait_for,
            max_wait_time_secs,
            profile,
            keep_alive,
        )


def publish_loop(
    conn: Connection,
    topic: str,
    message_type: str,
    values: str,
    period: float,
    print_nth: int,
    times: int,
    wait_for: int,
    max_wait: float | None,
    profile: QoSProfile,
    keep_alive: float,
) -> None:
    """ros2cli's order: check the type and YAML, wait for subscribers, fill, publish."""
    from ros2lite.interfaces import get_interface, set_message_fields
    from ros2lite.interfaces.registry import normalize_name

    node = conn.node()
    known_type(conn, normalize_name(message_type), topic)
    type_name = message_type_name(message_type)
    fields = yaml_fields(values)
    pub = node.create_publisher(type_name, topic, profile)
    if wait_for == 0 and max_wait is not None:
        raise CliError(
            '--max-wait-time-secs option is only effective with '
            '--wait-matching-subscriptions, --once or --times'
        )
    waited = 0.0
    ticks = 0
    while pub.get_subscription_count() < wait_for:
        if not ticks:  # say so once a second, look ten times a second
            click.echo(f'Waiting for at least {wait_for} matching subscription(s)...')
        if max_wait is not None and max_wait <= waited:
            raise CliError(
                f'Timed out waiting for subscribers: Expected {wait_for} subcribers '
                f'but only got {pub.get_subscription_count()} subscribers'
            )
        ticks = (ticks + 1) % 10
        time.sleep(WAIT_STEP)
        waited += WAIT_STEP

    msg = get_interface(type_name)()
    try:
        stamp_setters = set_message_fields(
            msg, message_fields(type(msg), fields), expand_header_auto=True, expand_time_now=True
        )
    except Exception as e:  # any reason the values do not fit, as ros2cli reports it
        raise CliError(f'Failed to populate field: {e}') from None
    click.echo('publisher: beginning loop')
    count = 0
    clock = node.get_clock()
    out = sys.stdout

    def publish_one() -> None:
        nonlocal count
        if stamp_setters:
            now = clock.now().to_msg()
            for setter in stamp_setters:
                setter(now)
        count += 1
        if print_nth and count % print_nth == 0:
            out.write(f'publishing #{count}: {msg!r}\n\n')
        pub.publish(msg)

    publish_one()
    if times != 1:
        timer = node.create_timer(period, publish_one)
        conn.spin_until(lambda: times != 0 and count >= times)
        node.destroy_timer(timer)
    time.sleep(keep_alive)  # let the last samples reach the wire before the session closes
