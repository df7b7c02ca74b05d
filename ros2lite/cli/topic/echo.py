"""`topic echo`: print the messages of a topic as YAML, CSV or raw CDR bytes."""

from __future__ import annotations

import sys
import time
from collections.abc import Callable
from typing import Any

import click

from .. import completion
from ..common import CliSession, explicit_qos, qos_from_options, qos_options, strategy_options
from ..errors import CliError

DEFAULT_TRUNCATE_LENGTH = 128
CLEAR_SCREEN = '\x1b[H\x1b[2J'


# -- helpers shared by echo, hz, bw and delay ---------------------------------------------------


def resolve_topic(node: Any, topic: str) -> str:
    """The fully qualified name of `topic` as the CLI node sees it; bad names are errors."""
    try:
        name: str = node.resolve_topic_name(topic)
    except ValueError as e:
        raise CliError(str(e)) from None
    return name


def graph_type(session: CliSession, topic: str, full_name: str) -> str | None:
    """The one type the graph knows for a topic (None if no endpoint uses it yet)."""
    from ros2lite.topic_monitor import topic_types

    types = topic_types(session.entities(), full_name)
    if len(types) > 1:
        raise CliError(
            f"Cannot echo topic '{topic}', as it contains more than one type: [{', '.join(types)}]"
        )
    return types[0] if types else None


def wait_for_type(session: CliSession, topic: str, full_name: str) -> str:
    """Block until some endpoint announces the topic, warning once, as ros2cli does."""
    found = graph_type(session, topic, full_name)
    if found is None:
        click.echo(f'WARNING: topic [{topic}] does not appear to be published yet')
        while found is None:
            time.sleep(0.1)
            found = graph_type(session, topic, full_name)
    return found


def message_type_name(name: str) -> str:
    """Validate a user-given message type ('pkg/msg/Name' or 'pkg/Name')."""
    from ros2lite.interfaces import InterfaceError, get_interface
    from ros2lite.interfaces.registry import normalize_name

    try:
        full = normalize_name(name)
        if full.split('/')[1] != 'msg':
            raise ValueError(name)
        get_interface(full)
    except (InterfaceError, ValueError, LookupError):
        raise CliError('The passed message type is invalid') from None
    return full


def compile_filter(expr: str | None) -> Callable[[Any], Any] | None:
    """`--filter EXPR` as a function of the message `m` (Python builtins available)."""
    if not expr:
        return None
    try:
        code = compile(expr, '<filter>', 'eval')
    except SyntaxError as e:
        raise CliError(f"Invalid filter expression '{expr}': {e.msg}") from None

    def check(m: Any) -> Any:
        return eval(code, {'__builtins__': __builtins__}, {'m': m})

    return check


def spin(
    session: CliSession,
    node: Any,
    done: Callable[[], bool] | None = None,
    deadline: float | None = None,
) -> None:
    """Run the node's callbacks until `done()` holds or the monotonic `deadline` passes."""
    from ros2lite.executors import SingleThreadedExecutor

    executor = SingleThreadedExecutor(context=session.context)
    executor.add_node(node)
    while session.context.ok() and not (done is not None and done()):
        if deadline is None:
            executor.spin_once(0.5)
            continue
        remaining = deadline - time.monotonic()
        if remaining <= 0:
            return
        executor.spin_once(min(remaining, 0.5))


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
        filter_fn: Callable[[Any], Any] | None,
        once: bool,
        include_info: bool,
        clear: bool,
        lost: Any,
    ) -> None:
        from ros2lite.interfaces import deserialize
        from ros2lite.interfaces.classes import Message

        self._deserialize = deserialize
        self._message_class = Message
        self.type_name = type_name
        self.csv = csv
        self.field = field
        self.fmt = {'truncate_length': truncate_length, 'no_arr': no_arr, 'no_str': no_str}
        self.flow_style = flow_style
        self.raw = raw
        self.filter_fn = filter_fn
        self.once = once
        self.include_info = include_info
        self.clear = clear
        self.lost = lost
        self.done = False
        self.out = sys.stdout

    def report_lost(self) -> None:
        for change, total in self.lost.drain():
            self.out.write(
                f'A message was lost!!!\n\ttotal count change:{change}\n\ttotal count: {total}---\n'
            )

    def __call__(self, data: bytes, info: Any) -> None:
        if self.lost is not None:
            self.report_lost()
        value: Any = data if self.raw else self._deserialize(self.type_name, data)
        if self.field is not None:
            for name in self.field:
                try:
                    value = getattr(value, name)
                except AttributeError as e:
                    raise CliError(f"Invalid field '{'.'.join(self.field)}': {e}") from None
        if self.filter_fn is not None and not self.filter_fn(value):
            return
        if self.once:
            self.done = True
        self.out.write(self.render(value, info))

    def render(self, value: Any, info: Any) -> str:
        from ros2lite.interfaces import message_to_csv, message_to_yaml

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


def info_dict(info: Any) -> dict[str, int]:
    """rclpy's message-info dict; rmw_zenoh has no reception sequence number and says 0."""
    return {
        'source_timestamp': info.source_timestamp,
        'received_timestamp': info.received_timestamp,
        'publication_sequence_number': info.publication_sequence_number,
        'reception_sequence_number': 0,
    }


@click.command('echo')
@click.argument('topic_name', shell_complete=completion.topics)
@click.argument('message_type', required=False, shell_complete=completion.message_types)
@strategy_options()
@qos_options('sensor_data')
@click.option(
    '--csv',
    is_flag=True,
    help='Output all recursive fields separated by commas (e.g. for plotting). With '
    '--include-message-info the source_timestamp, received_timestamp, '
    'publication_sequence_number and reception_sequence_number come first.',
)
@click.option(
    '--field',
    help="Echo a selected field of a message; use '.' to select "
    "sub-fields (e.g. 'pose.pose.position')",
)
@click.option(
    '-f',
    '--full-length',
    is_flag=True,
    help='Output all elements of arrays, bytes and strings longer than --truncate-length',
)
@click.option(
    '-l',
    '--truncate-length',
    type=click.IntRange(min=0),
    default=DEFAULT_TRUNCATE_LENGTH,
    show_default=True,
    help='The length to truncate arrays, bytes, and strings to',
)
@click.option('--no-arr', is_flag=True, help="Don't print array fields of messages")
@click.option('--no-str', is_flag=True, help="Don't print string fields of messages")
@click.option(
    '--flow-style',
    is_flag=True,
    help='Print collections in the flow style (not available with csv format)',
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
    type=click.FloatRange(min=0, min_open=True),
    metavar='N',
    help='Stop after N seconds (exit status 0)',
)
@click.option(
    '-i', '--include-message-info', is_flag=True, help='Shows the associated message info'
)
@click.option('-c', '--clear', is_flag=True, help='Clear the screen before each message')
@click.option('-n', '--node-name', help='Name of the created subscribing node')
def cli(
    topic_name: str,
    message_type: str | None,
    csv: bool,
    field: str | None,
    full_length: bool,
    truncate_length: int,
    no_arr: bool,
    no_str: bool,
    flow_style: bool,
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
    **qos: Any,
) -> None:
    """Output messages from a topic."""
    fields: list[str] | None = None
    if field is not None:
        fields = [f for f in field.split('.') if f]
        if not fields:
            raise CliError(f"Invalid field value '{field}'")
    filter_fn = compile_filter(filter_expr)
    deadline = None if timeout is None else time.monotonic() + timeout
    with CliSession(no_daemon=no_daemon, use_sim_time=use_sim_time) as session:
        node = session.node(node_name)
        full_name = resolve_topic(node, topic_name)
        profile = choose_qos(session, full_name, qos)
        if message_type is None:
            type_name = graph_type(session, topic_name, full_name)
            if type_name is None:
                click.echo(f'WARNING: topic [{topic_name}] does not appear to be published yet')
                raise CliError('Could not determine the type for the passed topic')
        else:
            type_name = message_type_name(message_type)
            warn_type_mismatch(session, full_name, type_name)
        lost = None
        if not no_lost_messages:
            from ros2lite.topic_stats import LostMessageCounter

            lost = LostMessageCounter()
        printer = Printer(
            type_name=type_name,
            csv=csv,
            field=fields,
            truncate_length=None if full_length else truncate_length,
            no_arr=no_arr,
            no_str=no_str,
            flow_style=flow_style,
            raw=raw,
            filter_fn=filter_fn,
            once=once,
            include_info=include_message_info,
            clear=clear,
            lost=lost,
        )
        if lost is not None:
            from ros2lite.topic_monitor import MonitoredSubscription

            counter = lost
            MonitoredSubscription(
                node,
                type_name,
                full_name,
                printer,
                profile,
                on_arrival=lambda _n, att, _t: counter.observe_attachment(att),
            )
        else:
            node.create_subscription(type_name, full_name, printer, profile, raw=True)
        spin(session, node, lambda: printer.done, deadline)


def warn_type_mismatch(session: CliSession, full_name: str, type_name: str) -> None:
    """Say at once when no publisher uses the asked type (or its hash): the data key holds
    both, so such a subscription would wait forever in silence."""
    from ros2lite.graph import endpoints_by_topic
    from ros2lite.interfaces import type_hash
    from ros2lite.transport.keys import EntityKind

    pubs = endpoints_by_topic(session.entities(), full_name, EntityKind.PUBLISHER)
    ours = type_hash(type_name)
    if not pubs or any(p.topic_type == type_name and p.topic_type_hash == ours for p in pubs):
        return
    names = sorted({p.topic_type for p in pubs})
    if type_name in names:
        hashes = sorted({p.topic_type_hash for p in pubs if p.topic_type == type_name})
        why = (
            f'as {type_name} with type hash {", ".join(hashes)}, not {ours} (another '
            'definition of the type)'
        )
    else:
        why = f'as {", ".join(names)}, not {type_name}'
    click.echo(
        f"WARNING: topic '{full_name}' is published {why}; nothing will arrive until a "
        f'matching publisher appears',
        err=True,
    )


def choose_qos(session: CliSession, full_name: str, options: dict[str, Any]) -> Any:
    """The `--qos-*` profile, or the preset adapted to what every publisher offers."""
    profile = qos_from_options(**options)
    if explicit_qos(**options):
        return profile
    from ros2lite.graph import endpoints_by_topic
    from ros2lite.topic_monitor import match_publishers_qos
    from ros2lite.transport.keys import EntityKind

    pubs = endpoints_by_topic(session.entities(), full_name, EntityKind.PUBLISHER)
    matched = match_publishers_qos(profile, [p.qos_profile for p in pubs])
    if matched.reliability_fell_back:
        click.echo(
            'Some, but not all, publishers are offering QoSReliabilityPolicy.RELIABLE. '
            'Falling back to QoSReliabilityPolicy.BEST_EFFORT as it will connect to '
            'all publishers'
        )
    if matched.durability_fell_back:
        click.echo(
            'Some, but not all, publishers are offering '
            'QoSDurabilityPolicy.TRANSIENT_LOCAL. Falling back to '
            'QoSDurabilityPolicy.VOLATILE as it will connect to all publishers'
        )
    return matched.profile
