"""Every option the verbs share, as click decorators: ros2cli's strategy options (same
names), the list/find flags, the YAML values argument, the `--qos-*` options and the profile
they describe, and the echo verbs' message-format options.

`--spin-time` is accepted for compatibility only: ros2lite answers graph questions from a
complete liveliness query, so there is nothing to wait for.
"""

from __future__ import annotations

import dataclasses
import functools
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, Any, TypedDict, TypeVar, cast

import click

from . import numbers

if TYPE_CHECKING:
    from _typeshed import DataclassInstance
    from typing_extensions import Unpack

    from ros2lite.qos import (
        DurabilityPolicy,
        HistoryPolicy,
        LivelinessPolicy,
        QoSProfile,
        ReliabilityPolicy,
    )

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
D = TypeVar('D', bound='DataclassInstance')

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


def json_option(what: str = 'one JSON document') -> Callable[[F], F]:
    """`--json` of every verb that prints data (`as_json`); `what` says what it prints (the
    README's schema section is the reference)."""
    return click.option(
        '--json', 'as_json', is_flag=True, help=f'Print {what} (schema 1, see the README)'
    )


NDJSON = 'NDJSON: one JSON object per line'


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
# an option decorator, as click.option makes them
_Decorator = Callable[[Callable[..., object]], Callable[..., object]]
CSV_HELP = 'Output all recursive fields separated by commas (e.g. for plotting)'


def format_options(
    *, csv_help: str = CSV_HELP, after_csv: Sequence[_Decorator] = ()
) -> Callable[[F], F]:
    """The echo verbs' message-format options (--csv, then `after_csv`, -f/--full-length,
    -l/--truncate-length, --no-arr, --no-str, --flow-style), handed to the verb as one
    `fmt: MessageFormat` argument (the truncation already None with --full-length)."""

    def decorate(fn: F) -> F:
        @functools.wraps(fn)
        def verb(
            *args: object,
            csv: bool,
            full_length: bool,
            truncate_length: int,
            no_arr: bool,
            no_str: bool,
            flow_style: bool,
            **kwargs: object,
        ) -> object:
            fmt: MessageFormat = {
                'csv': csv,
                'flow_style': flow_style,
                'truncate_length': None if full_length else truncate_length,
                'no_arr': no_arr,
                'no_str': no_str,
            }
            return fn(*args, fmt=fmt, **kwargs)

        opts: list[_Decorator] = [
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
        decorated: Callable[..., object] = verb
        for opt in reversed(opts):
            decorated = opt(decorated)
        return cast(F, decorated)

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


def bind(load: Callable[[], type[D]], to: str = 'options') -> Callable[[F], F]:
    """Hand the verb, as its one `to` argument, the dataclass `load()` returns filled from the
    click values named as its fields (click's tuples become lists); the other values reach the
    verb as before. A field whose option means something else (milliseconds, names still to
    resolve) gets a dest of its own, or the verb sets it with `dataclasses.replace`. `load`
    runs when the verb does, so the library's class stays out of `--help`."""

    def decorate(fn: F) -> F:
        @functools.wraps(fn)
        def verb(*args: object, **kwargs: object) -> object:
            cls = load()
            values = {
                f.name: _field_value(kwargs.pop(f.name))
                for f in dataclasses.fields(cls)
                if f.init and f.name in kwargs
            }
            return fn(*args, **{to: cls(**values)}, **kwargs)

        return cast(F, verb)

    return decorate


def _field_value(value: object) -> object:
    return list(value) if isinstance(value, tuple) else value


def plot_options(*, live: bool) -> Callable[[F], F]:
    """The options `topic plot` and `bag plot` share: what kind of plot, and where it goes
    instead of the terminal (a picture file, CSV rows)."""

    def decorate(fn: F) -> F:
        opts = [
            click.option(
                '--xy',
                is_flag=True,
                help='Plot one field against another of the same topic '
                '(/odom/pose/pose/position/x,y) instead of against time',
            ),
            click.option(
                '--snapshot',
                is_flag=True,
                help="Plot the newest value of an array field against its index (a LaserScan's "
                'ranges as a profile)' + ('' if live else '; a bag shows its last message'),
            ),
            click.option(
                '--header-stamp',
                is_flag=True,
                help='Time on x from the header stamp of each message, not its '
                + ('arrival' if live else 'log time'),
            ),
            click.option(
                '--png',
                'png_path',
                metavar='FILE',
                help='Write the plot as a PNG picture instead of drawing it',
            ),
            click.option(
                '--svg',
                'svg_path',
                metavar='FILE',
                help='Write the plot as an SVG picture instead of drawing it',
            ),
            click.option(
                '--csv',
                'csv_out',
                is_flag=True,
                help='Print the samples as CSV (time, then each value as topic echo --csv '
                'writes it) instead of drawing',
            ),
            click.option(
                '--size',
                type=numbers.Size(),
                default='800x480',
                show_default=True,
                metavar='WxH',
                help='Size of a picture in pixels',
            ),
        ]
        for opt in reversed(opts):
            fn = opt(fn)
        return fn

    return decorate
