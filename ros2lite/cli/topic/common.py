"""What the topic verbs share: parsing a message type and a `--filter`, and watching a topic
through the library's TopicMonitor with ros2cli's words around it."""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any, TypeVar

import click

from .. import numbers
from ..errors import CliError
from ..options import explicit_qos, qos_from_options

F = TypeVar('F', bound=Callable[..., Any])

if TYPE_CHECKING:
    from ros2lite.monitor.topic import TopicMonitor
    from ros2lite.qos import QoSProfile
    from ros2lite.tools.connection import Connection

    from ..options import QosOptions


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


def compile_filter(expr: str | None) -> Callable[[object], object] | None:
    """`--filter EXPR` as a function of the message `m` (Python builtins available), as
    ros2cli has it: the user's own expression, run in this process."""
    if not expr:
        return None
    try:
        code = compile(expr, '<filter>', 'eval')
    except SyntaxError as e:
        raise CliError(f"Invalid filter expression '{expr}': {e.msg}") from None

    def check(m: object) -> object:
        return eval(code, {'__builtins__': __builtins__}, {'m': m})

    return check


def window_option(default: int, what: str, minimum: int = 1) -> Callable[[F], F]:
    """`-w/--window N`: how many messages the statistics of `hz`, `bw` and `delay` span."""
    return click.option(
        '-w',
        '--window',
        'window',
        type=numbers.Count(min=minimum, max=10_000_000),
        default=default,
        show_default=True,
        metavar='WINDOW',
        help=f'{what} size, in # of messages, for calculating rate',
    )


def watch(conn: Connection, topic: str) -> tuple[TopicMonitor, str]:
    """A monitor of `topic` and its type, waited for with ros2cli's warning."""
    watched = monitor(conn, topic)
    type_name = graph_type(watched, wait=True)
    assert type_name is not None  # waiting ends only with a type
    return watched, type_name


def monitor(conn: Connection, topic: str, node_name: str | None = None) -> TopicMonitor:
    """A monitor of `topic` from this run's hidden node."""
    from ros2lite.monitor.topic import TopicMonitor

    return TopicMonitor(conn.node(node_name), topic, conn.entities)


def graph_type(watch: TopicMonitor, *, wait: bool = False) -> str | None:
    """The topic's one type in the graph (waiting for it with ros2cli's warning if asked),
    or None; ros2cli's error when it has several."""
    from ros2lite.monitor.topic import MultipleTypesError

    try:
        if not wait:
            return watch.graph_type()
        return watch.wait_for_type(
            lambda: click.echo(f'WARNING: topic [{watch.name}] does not appear to be published yet')
        )
    except MultipleTypesError as e:
        raise CliError(
            f"Cannot echo topic '{watch.name}', as it contains more than one type: "
            f'[{", ".join(e.types)}]'
        ) from None


def warn_type_mismatch(watch: TopicMonitor, type_name: str) -> None:
    """Say at once when no publisher uses the asked type (or its hash): such a subscription
    would wait forever in silence."""
    mismatch = watch.type_mismatch(type_name)
    if mismatch is None:
        return
    hint = ''
    if mismatch.same_name:
        why = (
            f'as {type_name} with type hash {", ".join(mismatch.published_hashes)}, not '
            f'{mismatch.type_hash} (another definition of the type)'
        )
    else:
        from ros2lite.pkg.distro import other_distro_name

        why = f'as {", ".join(mismatch.published_types)}, not {type_name}'
        hint = other_distro_name(type_name, list(mismatch.published_types))
    click.echo(
        f"WARNING: topic '{watch.topic}' is published {why}; nothing will arrive until a "
        f'matching publisher appears' + (f' ({hint})' if hint else ''),
        err=True,
    )


def choose_qos(watch: TopicMonitor, options: QosOptions, *, err: bool = False) -> QoSProfile:
    """The `--qos-*` profile, or the preset adapted to what every publisher offers (saying
    so on stdout as ros2cli does, or on stderr with `err`, when stdout carries data)."""
    profile = qos_from_options(**options)
    if explicit_qos(**options):
        return profile
    matched = watch.matched_qos(profile)
    if matched.reliability_fell_back:
        click.echo(
            'Some, but not all, publishers are offering QoSReliabilityPolicy.RELIABLE. '
            'Falling back to QoSReliabilityPolicy.BEST_EFFORT as it will connect to '
            'all publishers',
            err=err,
        )
    if matched.durability_fell_back:
        click.echo(
            'Some, but not all, publishers are offering '
            'QoSDurabilityPolicy.TRANSIENT_LOCAL. Falling back to '
            'QoSDurabilityPolicy.VOLATILE as it will connect to all publishers',
            err=err,
        )
    return matched.profile
