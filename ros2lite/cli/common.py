"""Pieces every graph verb shares: connecting (the library's Connection: daemon auto-start,
the hidden CLI node, graph snapshots, spinning) and the `--qos-*` options.

ros2cli's strategy options are accepted with the same names. `--spin-time` is accepted for
compatibility only: ros2lite answers graph questions from a complete liveliness query, so there
is nothing to wait for.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any, TypedDict, TypeVar

import click

from .errors import CliError

if TYPE_CHECKING:
    from typing_extensions import Unpack

    from ros2lite.connection import Connection
    from ros2lite.graph import Entity
    from ros2lite.qos import QoSProfile


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
            type=float,
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


def connect(*, no_daemon: bool = False, use_sim_time: bool = False) -> Connection:
    """This run's connection to the graph (the daemon started on demand unless
    `--no-daemon`); use it as a context manager."""
    from ros2lite.connection import Connection

    return Connection(autostart=not no_daemon, use_sim_time=use_sim_time)


def qos_options(default_profile: str) -> Callable[[F], F]:
    """The `--qos-*` options of `topic pub`/`echo` (ros2cli's add_qos_arguments)."""

    def decorate(fn: F) -> F:
        opts = [
            click.option(
                '--qos-liveliness-lease-duration-seconds',
                type=float,
                help='Quality of service liveliness lease duration in seconds',
            ),
            click.option(
                '--qos-liveliness',
                type=click.Choice(
                    ['system_default', 'automatic', 'manual_by_topic', 'unknown', 'best_available']
                ),
                help='Quality of service liveliness setting',
            ),
            click.option(
                '--qos-durability',
                type=click.Choice(
                    ['system_default', 'transient_local', 'volatile', 'unknown', 'best_available']
                ),
                help='Quality of service durability setting',
            ),
            click.option(
                '--qos-reliability',
                type=click.Choice(
                    ['system_default', 'reliable', 'best_effort', 'unknown', 'best_available']
                ),
                help='Quality of service reliability setting',
            ),
            click.option(
                '--qos-history',
                type=click.Choice(['system_default', 'keep_last', 'keep_all', 'unknown']),
                help='Quality of service history setting',
            ),
            click.option(
                '--qos-depth',
                type=click.IntRange(min=0),
                help='Queue size setting (overrides depth value of --qos-profile option)',
            ),
            click.option(
                '--qos-profile',
                type=click.Choice(QOS_PROFILES),
                default=default_profile,
                show_default=True,
                help='Quality of service preset profile',
            ),
        ]
        for opt in opts:
            fn = opt(fn)
        return fn

    return decorate


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
    changes: dict[str, object] = {}
    if qos_history is not None:
        changes['history'] = q.HistoryPolicy.from_short_key(qos_history)
    if qos_reliability is not None:
        changes['reliability'] = q.ReliabilityPolicy.from_short_key(qos_reliability)
    if qos_durability is not None:
        changes['durability'] = q.DurabilityPolicy.from_short_key(qos_durability)
    if qos_liveliness is not None:
        changes['liveliness'] = q.LivelinessPolicy.from_short_key(qos_liveliness)
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


def include_hidden(ctx: click.Context, flag: bool = False) -> bool:
    """--include-hidden-topics given on the verb or on `topic` itself (whose flag reaches
    the verb through click's shared context object)."""
    return flag or bool((ctx.obj or {}).get('include_hidden_topics'))


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
        click.echo('\n'.join(f'{n} [{", ".join(t)}]' if types else n for n, t in names_and_types))


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
    ctx: click.Context,
    name: str,
    no_daemon: bool,
    names_and_types: Callable[[list[Entity]], list[tuple[str, list[str]]]],
) -> None:
    """What `topic/service/action type` share: the type(s) of `name` in the graph, or exit 1
    without a word, as ros2cli does (a name that cannot be valid is just an unknown one)."""
    from ros2lite.names import expand_topic_name

    try:
        full = expand_topic_name(name, 'ros2lite', '/')
    except ValueError:
        ctx.exit(1)
    with connect(no_daemon=no_daemon) as conn:
        entities = conn.entities()
    types = dict(names_and_types(entities)).get(full)
    if types is None:
        ctx.exit(1)
    click.echo('\n'.join(types))


class ManyValues(click.Option):
    '''An option that takes every following word up to the next option, as argparse's
    `nargs='+'` does (`--topics /a /b -o out`). It may also be repeated.'''

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        kwargs.setdefault('multiple', True)
        super().__init__(*args, **kwargs)

    def add_to_parser(self, parser: Any, ctx: click.Context) -> None:
        super().add_to_parser(parser, ctx)
        for name in self.opts:
            opt = parser._long_opt.get(name) or parser._short_opt.get(name)
            if opt is None:
                continue
            previous = opt.process

            def process(value: Any, state: Any, previous: Any = previous) -> None:
                values = [value]
                while state.rargs and not state.rargs[0].startswith('-'):
                    values.append(state.rargs.pop(0))
                for v in values:
                    previous(v, state)

            opt.process = process
