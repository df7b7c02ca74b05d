"""`topic echo`: print the messages of a topic as YAML, CSV or raw CDR bytes."""

from __future__ import annotations

import sys
from collections.abc import Callable
from typing import TYPE_CHECKING

import click

from .. import completion, numbers
from ..common import connect, known_type
from ..errors import CliError
from ..options import (
    CSV_HELP,
    NDJSON,
    format_options,
    json_option,
    qos_options,
    strategy_options,
)
from ..parsing import command
from .common import (
    choose_qos,
    compile_filter,
    graph_type,
    message_type_name,
    monitor,
    warn_type_mismatch,
)

if TYPE_CHECKING:
    from typing_extensions import Unpack

    from ros2lite.interfaces.convert import FormatOptions
    from ros2lite.interfaces.parser import FieldType
    from ros2lite.monitor.stats import LostMessageCounter
    from ros2lite.subscription import MessageInfo

    from ..options import MessageFormat, QosOptions

PRUNE_PERIOD = 5.0  # seconds between prunings of the lost-message table
CLEAR_SCREEN = '\x1b[H\x1b[2J'


# -- echo -----------------------------------------------------------------------------------------


class Printer:
    """Turns each received sample into ros2cli's text for the chosen options."""

    def __init__(
        self,
        *,
        type_name: str,
        csv: bool,
        field: list[str] | None,
        truncate_length: int | None,
        no_arr: bool,
        no_str: bool,
        flow_style: bool,
        raw: bool,
        filter_fn: Callable[[object], object] | None,
        once: bool,
        include_info: bool,
        clear: bool,
        lost: LostMessageCounter | None,
        warn: Callable[[str], object],
        topic: str = '',
        as_json: bool = False,
    ) -> None:
        from ros2lite.interfaces import deserialize
        from ros2lite.interfaces.classes import Message
        from ros2lite.runtime.bad_samples import BadSamples

        self._deserialize = deserialize
        self._message_class = Message
        self.type_name = type_name
        self.csv = csv
        self.field = field
        self.fmt: FormatOptions = {
            'truncate_length': truncate_length,
            'no_arr': no_arr,
            'no_str': no_str,
        }
        self.flow_style = flow_style
        self.raw = raw
        self.filter_fn = filter_fn
        self.once = once
        self.include_info = include_info
        self.clear = clear
        self.lost = lost
        self.as_json = as_json
        self.field_type: FieldType | None = None  # of the --field value, once known
        self.done = False
        self.out = sys.stdout
        self.bad = BadSamples(topic, type_name, warn)

    def report_lost(self) -> None:
        """Print ros2cli's lines for messages lost since the last call."""
        if self.lost is None:
            return
        for change, total in self.lost.drain():
            # NDJSON holds messages only: the notice goes where errors go
            (sys.stderr if self.as_json else self.out).write(
                f'A message was lost!!!\n\ttotal count change:{change}\n\ttotal count: {total}---\n'
            )

    def __call__(self, data: bytes, info: MessageInfo) -> None:
        if self.lost is not None:
            self.report_lost()
        from ros2lite.interfaces import CdrError

        try:
            value: object = data if self.raw else self._deserialize(self.type_name, data)
        except CdrError as e:
            self.bad_sample(data, info, e)
            return
        if self.field is not None:
            for name in self.field:
                parent = value
                try:
                    value = getattr(value, name)
                except AttributeError as e:
                    raise CliError(f"Invalid field '{'.'.join(self.field)}': {e}") from None
            if self.as_json and self.field_type is None:
                from ros2lite.interfaces.convert import field_type

                self.field_type = field_type(parent, self.field[-1])
        if self.filter_fn is not None and not self.filter_fn(value):
            return
        if self.once:
            self.done = True
        self.out.write(self.render(value, info))
        if self.as_json:
            self.out.flush()

    def bad_sample(self, data: bytes, info: MessageInfo, error: Exception) -> None:
        """A sample that is not the type: dropped with a (rate-limited) warning, or shown
        with its message info when the user asked for message info."""
        from ros2lite.runtime.bad_samples import describe_publisher

        self.bad.add(info.publisher_gid, error, len(data))
        if not self.include_info or self.as_json:
            return
        head = ''.join(f'{k}: {v}\n' for k, v in sorted(info_dict(info).items()))
        self.out.write(
            f'{head}---\n# dropped: not a valid {self.type_name} from '
            f'{describe_publisher(info.publisher_gid)} ({len(data)} bytes: {error})\n---\n'
        )

    def render(self, value: object, info: MessageInfo) -> str:
        from ros2lite.interfaces import message_to_csv, message_to_yaml

        if self.as_json:
            return self.render_json(value, info)
        head = CLEAR_SCREEN if self.clear else ''
        if not isinstance(value, self._message_class):
            if self.include_info:
                head += (
                    '---Got new message, message info:---\n'
                    f'{info_dict(info)}\n---Message data:---\n'
                )
            return f'{head}{value}\n---\n'
        if self.csv:
            text = message_to_csv(value, **self.fmt)
            if self.include_info:
                text = ','.join(str(v) for v in info_dict(info).values()) + ',' + text
            return f'{head}{text}\n'
        if self.include_info:
            # what yaml.dump() makes of the info dict: sorted keys, plain integers
            head += ''.join(f'{k}: {v}\n' for k, v in sorted(info_dict(info).items())) + '---\n'
        return head + message_to_yaml(value, flow_style=self.flow_style, **self.fmt) + '---\n'

    def render_json(self, value: object, info: MessageInfo) -> str:
        """One NDJSON line: the message (or --field value; --raw: the CDR bytes as base64)
        in the JSON form, inside `{"message", "info"}` when message info was asked for.
        Always full length; --no-arr/--no-str put their placeholder strings in."""
        import base64

        from ros2lite.interfaces.json_form import dumps, echo_record, value_to_json

        obj: object
        if isinstance(value, bytes) and self.raw:
            obj = base64.b64encode(value).decode('ascii')
        else:
            obj = value_to_json(
                value, self.field_type, no_arr=self.fmt['no_arr'], no_str=self.fmt['no_str']
            )
        return dumps(echo_record(obj, info_dict(info) if self.include_info else None)) + '\n'


def info_dict(info: MessageInfo) -> dict[str, int]:
    """rclpy's message-info dict; rmw_zenoh has no reception sequence number and says 0."""
    return {
        'source_timestamp': info.source_timestamp,
        'received_timestamp': info.received_timestamp,
        'publication_sequence_number': info.publication_sequence_number,
        'reception_sequence_number': 0,
    }


@command('echo')
@click.argument('topic_name', shell_complete=completion.topics)
@click.argument('message_type', required=False, shell_complete=completion.message_types)
@strategy_options()
@qos_options('sensor_data')
@format_options(
    csv_help=f'{CSV_HELP}. With --include-message-info the source_timestamp, '
    'received_timestamp, publication_sequence_number and reception_sequence_number come first.',
    after_csv=[
        click.option(
            '--field',
            help="Echo a selected field of a message; use '.' to select "
            "sub-fields (e.g. 'pose.pose.position')",
        )
    ],
)
@click.option('--no-lost-messages', is_flag=True, help="Don't report when a message is lost")
@click.option('--raw', is_flag=True, help='Echo the raw binary representation')
@click.option(
    '--filter',
    'filter_expr',
    metavar='EXPR',
    help='Python expression to filter the messages printed; it can use Python '
    'builtins and m (the message)',
)
@click.option('--once', is_flag=True, help='Print the first message received and then exit')
@click.option(
    '--timeout',
    type=numbers.seconds(min_open=True),
    metavar='N',
    help='Stop after N seconds (exit status 0)',
)
@click.option(
    '-i', '--include-message-info', is_flag=True, help='Shows the associated message info'
)
@click.option('-c', '--clear', is_flag=True, help='Clear the screen before each message')
@click.option('-n', '--node-name', help='Name of the created subscribing node')
@json_option(f'each message in the JSON form ({NDJSON}; with -i: {{"message", "info"}})')
def cli(
    topic_name: str,
    message_type: str | None,
    fmt: MessageFormat,
    field: str | None,
    no_lost_messages: bool,
    raw: bool,
    filter_expr: str | None,
    once: bool,
    timeout: float | None,
    include_message_info: bool,
    clear: bool,
    node_name: str | None,
    use_sim_time: bool,
    no_daemon: bool,
    as_json: bool,
    **qos: Unpack[QosOptions],
) -> None:
    """Output messages from a topic."""
    if as_json and fmt['csv']:
        raise click.UsageError('--json and --csv are two formats: pick one')
    fields: list[str] | None = None
    if field is not None:
        fields = [f for f in field.split('.') if f]
        if not fields:
            raise CliError(f"Invalid field value '{field}'")
    from ros2lite.interfaces.registry import normalize_name

    filter_fn = compile_filter(filter_expr)
    with connect(no_daemon=no_daemon, use_sim_time=use_sim_time) as conn:
        watch = monitor(conn, topic_name, node_name)
        profile = choose_qos(watch, qos)
        if message_type is None:
            type_name = graph_type(watch)
            if type_name is None:
                click.echo(f'WARNING: topic [{topic_name}] does not appear to be published yet')
                raise CliError('Could not determine the type for the passed topic')
            known_type(conn, type_name, watch.topic)
        else:
            known_type(conn, normalize_name(message_type), watch.topic)
            type_name = message_type_name(message_type)
            warn_type_mismatch(watch, type_name)
        lost = None
        if not no_lost_messages:
            from ros2lite.monitor.stats import LostMessageCounter

            lost = LostMessageCounter()
        printer = Printer(
            type_name=type_name,
            field=fields,
            raw=raw,
            filter_fn=filter_fn,
            once=once,
            include_info=include_message_info,
            clear=clear,
            lost=lost,
            warn=watch.node.get_logger().warn,
            topic=watch.topic,
            as_json=as_json,
            **fmt,
        )
        if lost is not None:
            counter = lost
            # publishers that left are forgotten, so the table follows the graph
            conn.every(PRUNE_PERIOD, lambda: counter.prune(watch.publisher_gids()))
            watch.on_arrival(
                type_name,
                profile,
                lambda _n, att, _t: counter.observe_attachment(att),
                callback=printer,
            )
        else:
            watch.on_sample(type_name, profile, printer)
        conn.spin_until(lambda: printer.done, timeout)
