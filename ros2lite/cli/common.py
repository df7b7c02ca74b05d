"""Pieces every graph verb shares: connecting (the library's Connection: daemon auto-start,
the hidden CLI node, graph snapshots, spinning) and the `--qos-*` options.

ros2cli's strategy options are accepted with the same names. `--spin-time` is accepted for
compatibility only: ros2lite answers graph questions from a complete liveliness query, so there
is nothing to wait for.
"""

from __future__ import annotations

import functools
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, Any, TypedDict, TypeVar, cast

import click

from . import numbers, render
from .errors import CliError

if TYPE_CHECKING:
    from typing_extensions import Unpack

    from ros2lite.graph import Entity
    from ros2lite.interfaces import Message
    from ros2lite.node import Node
    from ros2lite.qos import (
        DurabilityPolicy,
        HistoryPolicy,
        LivelinessPolicy,
        QoSProfile,
        ReliabilityPolicy,
    )
    from ros2lite.tools.connection import Connection

    Policy = HistoryPolicy | ReliabilityPolicy | DurabilityPolicy | LivelinessPolicy


class QosOptions(TypedDict):
    """The values of the `--qos-*` options `qos_options()` adds."""

    qos_profile: str
    qos_depth: int | None
    qos_history: str | None
    qos_reliability: str | None
    qos_durability: str | None
    qos_liveliness: str | None
    qos_liveliness_lease_duration_seconds: float | None


F = TypeVar('F', bound=Callable[..., Any])

QOS_PROFILES = [
    'unknown',
    'default',
    'system_default',
    'sensor_data',
    'services_default',
    'parameters',
    'parameter_events',
    'action_status_default',
    'best_available',
]


def strategy_options(*, no_daemon: bool = True) -> Callable[[F], F]:
    """--spin-time, -s/--use-sim-time and (for graph queries) --no-daemon."""

    def decorate(fn: F) -> F:
        fn = click.option('-s', '--use-sim-time', is_flag=True, help='Enable ROS simulation time')(
            fn
        )
        # accepted so ros2cli command lines keep working, then dropped here once
        fn = click.option(
            '--spin-time',
            type=numbers.seconds(),
            default=0.5,
            show_default=True,
            expose_value=False,
            help='Accepted for ros2cli compatibility; graph queries here are '
            'complete without spinning',
        )(fn)
        if no_daemon:
            fn = click.option(
                '--no-daemon', is_flag=True, help='Do not spawn nor use an already running daemon'
            )(fn)
        return fn

    return decorate


def count_option(kind: str) -> Callable[[F], F]:
    """`-c/--count-<kind>` of the list and find verbs, in ros2cli's words."""
    return click.option(
        '-c', f'--count-{kind}', is_flag=True, help=f'Only display the number of {kind} discovered'
    )


def show_types_option(kind: str) -> Callable[[F], F]:
    """`-t/--show-types` of the verbs that list services or actions, in ros2cli's words."""
    return click.option(
        '-t', '--show-types', is_flag=True, help=f'Additionally show the {kind} type'
    )


def prefix_option(name: str, metavar: str, before: str, example: str) -> Callable[[F], F]:
    """The prefix command of `run` (`--prefix`) and `launch` (`--launch-prefix`), put before
    the executable(s) `before` names; ros2cli's wording, with `example` as its example."""
    return click.option(
        name,
        metavar=metavar,
        help=f'Prefix command, which should go before {before}. Command must be wrapped in '
        f"quotes if it contains spaces (e.g. {name} '{example}').",
    )


def values_argument(name: str = 'values', what: str = 'values') -> Callable[[F], F]:
    """The optional YAML argument `name` of pub/call/send_goal and its `--stdin` alternative
    (`what` the help reads: 'values', 'the goal'); see `check_stdin`."""

    def decorate(fn: F) -> F:
        fn = click.option(
            '--stdin', 'use_stdin', is_flag=True, help=f'Read {what} from standard input'
        )(fn)
        decorated: F = click.argument(name, required=False)(fn)
        return decorated

    return decorate


def check_stdin(values: str | None, use_stdin: bool, name: str = 'values') -> None:
    """ros2cli's usage error when both the YAML argument `name` and --stdin are given."""
    if use_stdin and values is not None:
        raise click.UsageError(f'argument --stdin: not allowed with argument {name}')


def yaml_fields(values: str, *, allow_empty: bool = False) -> dict[str, object]:
    """The field values given in YAML (VALUES or --stdin) as a mapping, or ros2cli's line
    saying why they are not one (`allow_empty`: empty text means no fields, as in
    `service call`)."""
    from ros2lite.util.safe_yaml import YamlInputError, load

    try:
        parsed = load(values, 'the passed value')
    except YamlInputError as e:
        if not e.syntax:
            raise CliError(str(e)) from None
        raise CliError('The passed value needs to be in YAML string or a dictionary') from None
    if parsed is None and allow_empty:
        return {}
    if not isinstance(parsed, dict):
        raise CliError('The passed value needs to be a dictionary in YAML format')
    return parsed


def connect(
    *, no_daemon: bool = False, use_sim_time: bool = False, as_node: bool = False
) -> Connection:
    """This run's connection to the graph (the daemon's graph cache asked, and the daemon
    started on demand, unless `--no-daemon`; a node's peer session with `as_node`); use it
    as a context manager."""
    from ros2lite.tools.connection import Connection

    return Connection(
        autostart=not no_daemon,
        use_sim_time=use_sim_time,
        as_node=as_node,
        graph_cache=not no_daemon,
    )


def _policies() -> list[tuple[str, type[Policy]]]:
    """The `--qos-<name>` policy options, in ros2cli's order, with the library's enums
    (whose short keys are the choices)."""
    from ros2lite import qos as q

    return [
        ('history', q.HistoryPolicy),
        ('reliability', q.ReliabilityPolicy),
        ('durability', q.DurabilityPolicy),
        ('liveliness', q.LivelinessPolicy),
    ]


def qos_options(default_profile: str) -> Callable[[F], F]:
    """The `--qos-*` options of `topic pub`/`echo` (ros2cli's add_qos_arguments)."""

    def decorate(fn: F) -> F:
        opts = [
            click.option(
                '--qos-profile',
                type=click.Choice(QOS_PROFILES),
                default=default_profile,
                show_default=True,
                help='Quality of service preset profile',
            ),
            click.option(
                '--qos-depth',
                type=numbers.Count(min=0),
                help='Queue size setting (overrides depth value of --qos-profile option)',
            ),
        ]
        for name, policy in _policies():
            # manual_by_node is deprecated in rmw: ros2cli does not offer it
            keys = [k for k in policy.short_keys() if k != 'manual_by_node']
            opts.append(
                click.option(
                    f'--qos-{name}',
                    type=click.Choice(keys),
                    help=f'Quality of service {name} setting',
                )
            )
        opts.append(
            click.option(
                '--qos-liveliness-lease-duration-seconds',
                type=numbers.seconds(),
                help='Quality of service liveliness lease duration in seconds',
            )
        )
        for opt in reversed(opts):
            fn = opt(fn)
        return fn

    return decorate


class MessageFormat(TypedDict):
    """How an echo verb prints a message, from `format_options()`: the keywords of the
    library's `format_event` (and of `topic echo`'s printer)."""

    csv: bool
    flow_style: bool
    truncate_length: int | None
    no_arr: bool
    no_str: bool


DEFAULT_TRUNCATE_LENGTH = 128
CSV_HELP = 'Output all recursive fields separated by commas (e.g. for plotting)'


def format_options(
    *, csv_help: str = CSV_HELP, after_csv: Sequence[Callable[[Any], Any]] = ()
) -> Callable[[F], F]:
    """The echo verbs' message-format options (--csv, then `after_csv`, -f/--full-length,
    -l/--truncate-length, --no-arr, --no-str, --flow-style), handed to the verb as one
    `fmt: MessageFormat` argument (the truncation already None with --full-length)."""

    def decorate(fn: F) -> F:
        @functools.wraps(fn)
        def verb(
            *args: Any,
            csv: bool,
            full_length: bool,
            truncate_length: int,
            no_arr: bool,
            no_str: bool,
            flow_style: bool,
            **kwargs: Any,
        ) -> Any:
            fmt: MessageFormat = {
                'csv': csv,
                'flow_style': flow_style,
                'truncate_length': None if full_length else truncate_length,
                'no_arr': no_arr,
                'no_str': no_str,
            }
            return fn(*args, fmt=fmt, **kwargs)

        opts = [
            click.option('--csv', is_flag=True, help=csv_help),
            *after_csv,
            click.option(
                '-f',
                '--full-length',
                is_flag=True,
                help='Output all elements of arrays, bytes and strings longer than '
                '--truncate-length',
            ),
            click.option(
                '-l',
                '--truncate-length',
                type=numbers.Count(min=0),
                default=DEFAULT_TRUNCATE_LENGTH,
                show_default=True,
                help='The length to truncate arrays, bytes, and strings to',
            ),
            click.option('--no-arr', is_flag=True, help="Don't print array fields of messages"),
            click.option('--no-str', is_flag=True, help="Don't print string fields of messages"),
            click.option(
                '--flow-style',
                is_flag=True,
                help='Print collections in the flow style (not available with csv format)',
            ),
        ]
        decorated: Any = verb
        for opt in reversed(opts):
            decorated = opt(decorated)
        return cast(F, decorated)

    return decorate


def print_event(msg: Message, fmt: MessageFormat, head: str = '') -> None:
    """Print one service event (or any message) as `service echo` and `action echo` do:
    `head`, the message, then `---` (a CSV line ends with its newline alone)."""
    import sys

    from ros2lite.service_introspection import format_event

    text = format_event(msg, **fmt)
    sys.stdout.write(head + text + ('\n' if fmt['csv'] else '---\n'))


def qos_from_options(
    qos_profile: str,
    qos_depth: int | None,
    qos_history: str | None,
    qos_reliability: str | None,
    qos_durability: str | None,
    qos_liveliness: str | None = None,
    qos_liveliness_lease_duration_seconds: float | None = None,
    **_: object,
) -> QoSProfile:
    """The profile the `--qos-*` options describe (unset options keep the preset's value)."""
    from ros2lite import qos as q

    profile = q.preset(qos_profile)
    given = {
        'history': qos_history,
        'reliability': qos_reliability,
        'durability': qos_durability,
        'liveliness': qos_liveliness,
    }
    changes: dict[str, object] = {
        name: policy.from_short_key(key)
        for name, policy in _policies()
        if (key := given[name]) is not None
    }
    if qos_liveliness_lease_duration_seconds is not None:
        changes['liveliness_lease_duration'] = q.Duration.from_seconds(
            qos_liveliness_lease_duration_seconds
        )
    if qos_depth is not None:
        changes['depth'] = qos_depth
    elif (
        changes.get('durability', profile.durability) == q.DurabilityPolicy.TRANSIENT_LOCAL
        and profile.depth == 0
    ):
        changes['depth'] = 1
    return profile.replace(**changes) if changes else profile


def explicit_qos(**options: Unpack[QosOptions]) -> bool:
    """True when any `--qos-*` override (other than the profile) was given."""
    return any(
        options.get(k) is not None
        for k in (
            'qos_depth',
            'qos_history',
            'qos_reliability',
            'qos_durability',
            'qos_liveliness',
            'qos_liveliness_lease_duration_seconds',
        )
    )


def resolved_name(node: Node, name: str, kind: str) -> str:
    """`name` resolved by the CLI's node as a `kind` ('service', 'action') name, or ros2cli's
    line saying it is invalid."""
    resolve = node.resolve_service_name if kind == 'service' else node.resolve_topic_name
    try:
        return resolve(name)
    except ValueError:
        raise CliError(f"The {kind} name '{name}' is invalid") from None


def interface_type_name(name: str, kind: str, *, invalid: str, not_kind: str | None = None) -> str:
    """A user-given 'pkg/Name' or 'pkg/<kind>/Name' as the full name of an existing
    interface of that kind; ros2cli's messages (`invalid`, `not_kind`) otherwise."""
    from ros2lite.interfaces import InterfaceError, get_interface

    parts = name.split('/')
    if len(parts) == 2:
        parts = [parts[0], kind, parts[1]]
    if len(parts) != 3 or not all(parts):
        raise CliError(invalid)
    full = '/'.join(parts)
    try:
        get_interface(full)
    except (InterfaceError, ValueError, LookupError):
        raise CliError(invalid) from None
    if parts[1] != kind:
        raise CliError(not_kind or invalid)
    return full


def print_names(names_and_types: list[tuple[str, list[str]]], count: bool, types: bool) -> None:
    """What the list and find verbs print: how many there are, or one name a line (with
    `[type, …]` when asked)."""
    if count:
        click.echo(len(names_and_types))
    elif names_and_types:
        render.echo('\n'.join(f'{n} [{", ".join(t)}]' if types else n for n, t in names_and_types))


def print_names_of_type(
    type_name: str,
    count: bool,
    no_daemon: bool,
    names_and_types: Callable[[list[Entity]], list[tuple[str, list[str]]]],
) -> None:
    """What `topic/service/action find` share: the names in the graph with `type_name`
    among their types, one a line, or only how many (`count`)."""
    with connect(no_daemon=no_daemon) as conn:
        entities = conn.entities()
    print_names(
        [(name, types) for name, types in names_and_types(entities) if type_name in types],
        count,
        types=False,
    )


def print_types_of(
    name: str,
    no_daemon: bool,
    names_and_types: Callable[[list[Entity]], list[tuple[str, list[str]]]],
    kind: str = 'topic',
) -> None:
    """What `topic/service/action type` share: the type(s) of `name` in the graph. Exit 1 as
    ros2cli does when there is none, with nothing on stdout (scripts read it) and one line
    on stderr saying why (ros2cli says nothing at all)."""
    from ros2lite.names import expand_topic_name

    try:
        full = expand_topic_name(name, 'ros2lite', '/', is_service=kind == 'service')
    except ValueError as e:
        raise CliError(str(e).replace('topic name', f'{kind} name', 1)) from None
    with connect(no_daemon=no_daemon) as conn:
        entities = conn.entities()
    types = dict(names_and_types(entities)).get(full)
    if types is None:
        raise CliError(f"Unknown {kind} '{full}' (not in the graph now)")
    render.echo('\n'.join(types))


def wait_saying_other_types(
    ready: Callable[[float], bool],
    timeout: float | None,
    kind: str,
    name: str,
    type_name: str,
    served_types: Callable[[], list[tuple[str, list[str]]]],
) -> bool:
    """Wait up to `timeout` s (None: for ever) until `ready(step)` holds, saying once on
    stderr when `name` is served with another type than `type_name` (such a wait would
    otherwise go on in silence, as ros2cli's does). True when ready."""
    import time

    deadline = None if timeout is None else time.monotonic() + timeout
    warned = False
    while True:
        left = None if deadline is None else max(0.0, deadline - time.monotonic())
        if ready(0.5 if left is None else min(0.5, left)):
            return True
        if not warned:
            others = sorted(
                {t for n, types in served_types() if n == name for t in types if t != type_name}
            )
            if others:
                warned = True
                click.echo(
                    f"WARNING: {kind} '{name}' is served as {', '.join(others)}, not "
                    f'{type_name}; nothing will answer until a server of {type_name} appears',
                    err=True,
                )
        if deadline is not None and time.monotonic() >= deadline:
            return False
