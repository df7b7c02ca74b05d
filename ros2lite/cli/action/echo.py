"""`action echo`: print what happens on an action — its three services' introspection events,
its feedback and its status — as Kilted's `ros2 action echo` does."""

from __future__ import annotations

import sys
from typing import TYPE_CHECKING, Any

import click

from .. import completion
from ..common import connect, interface_type_name, strategy_options
from ..errors import CliError

if TYPE_CHECKING:
    from ros2lite.subscription import MessageInfo

DEFAULT_TRUNCATE_LENGTH = 128


@click.command('echo')
@click.argument('action_name', shell_complete=completion.actions)
@click.argument('action_type', required=False, shell_complete=completion.action_types)
@strategy_options()
@click.option(
    '-i',
    '--interfaces',
    metavar='INTERFACES',
    help='The interfaces to print, separated by "|": GOAL_SERVICE, CANCEL_SERVICE, '
    'RESULT_SERVICE, FEEDBACK_TOPIC, STATUS_TOPIC (default: all of them)',
)
@click.option(
    '--csv',
    is_flag=True,
    help='Output all recursive fields separated by commas (e.g. for plotting)',
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
def cli(
    action_name: str,
    action_type: str | None,
    interfaces: str | None,
    csv: bool,
    full_length: bool,
    truncate_length: int,
    no_arr: bool,
    no_str: bool,
    flow_style: bool,
    no_daemon: bool,
    use_sim_time: bool,
) -> None:
    """Echo a action.

    The services show up only while action introspection is on at the server or the client
    (`configure_introspection`); feedback and status always do.
    """
    from ros2lite.action.introspection import INTERFACES, action_interfaces
    from ros2lite.graph import action_names_and_types
    from ros2lite.interfaces import deserialize
    from ros2lite.service_introspection import format_event

    wanted = set(INTERFACES)
    if interfaces is not None:
        if not interfaces:
            raise CliError('Input action interface name is empty.')
        wanted = set()
        for name in interfaces.split('|'):
            if name.strip().upper() not in INTERFACES:
                raise CliError(f'"{name.strip()}" is incorrect interface name.')
            wanted.add(name.strip().upper())
    with connect(no_daemon=no_daemon, use_sim_time=use_sim_time) as conn:
        node = conn.node()
        try:
            full = node.resolve_topic_name(action_name)
        except ValueError:
            raise CliError(f"The action name '{action_name}' is invalid") from None
        if action_type is not None:
            type_name = interface_type_name(
                action_type, 'action', invalid=f"The service type '{action_type}' is invalid"
            )
        else:
            types = dict(action_names_and_types(conn.entities(), include_hidden=True)).get(full)
            if not types:
                raise CliError(f"Could not load the action type for '{action_name}'")
            type_name = types[0]
        fmt: dict[str, Any] = {  # format_event's keywords
            'csv': csv,
            'flow_style': flow_style,
            'truncate_length': None if full_length else truncate_length,
            'no_arr': no_arr,
            'no_str': no_str,
        }
        for watched in action_interfaces(full, type_name):
            if watched.interface not in wanted:
                continue

            def show(
                data: bytes,
                _info: MessageInfo,
                name: str = watched.interface,
                t: str = watched.type_name,
            ) -> None:
                text = format_event(deserialize(t, data), **fmt)
                sys.stdout.write(f'interface: {name}\n{text}' + ('\n' if csv else '---\n'))

            node.create_subscription(watched.type_name, watched.topic, show, watched.qos, raw=True)
        conn.spin()
