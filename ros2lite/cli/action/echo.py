"""`action echo`: print what happens on an action — its three services' introspection events,
its feedback and its status — as Kilted's `ros2 action echo` does."""

from __future__ import annotations

from typing import TYPE_CHECKING

import click

from .. import completion
from ..common import connect, interface_type_name, resolved_name
from ..errors import CliError
from ..options import NDJSON, format_options, json_option, strategy_options
from ..parsing import command
from ..render import print_event

if TYPE_CHECKING:
    from ros2lite.interfaces import Message

    from ..options import MessageFormat


@command('echo')
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
@format_options()
@json_option(f'{{"interface", "message"}} per message ({NDJSON})')
def cli(
    action_name: str,
    action_type: str | None,
    interfaces: str | None,
    fmt: MessageFormat,
    no_daemon: bool,
    use_sim_time: bool,
    as_json: bool,
) -> None:
    """Echo a action.

    The services show up only while action introspection is on at the server or the client
    (`configure_introspection`); feedback and status always do.
    """
    from ros2lite.action.introspection import INTERFACES, action_interfaces
    from ros2lite.graph import action_names_and_types

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
        full = resolved_name(node, action_name, 'action')
        if action_type is not None:
            type_name = interface_type_name(
                action_type, 'action', invalid=f"The service type '{action_type}' is invalid"
            )
        else:
            types = dict(action_names_and_types(conn.entities(), include_hidden=True)).get(full)
            if not types:
                raise CliError(f"Could not load the action type for '{action_name}'")
            type_name = types[0]
        for watched in action_interfaces(full, type_name):
            if watched.interface not in wanted:
                continue

            def show(msg: Message, name: str = watched.interface) -> None:
                print_event(
                    msg,
                    fmt,
                    head=f'interface: {name}\n',
                    as_json={'interface': name} if as_json else None,
                )

            # typed: a sample that is not the type is dropped and reported, not fatal
            node.create_subscription(watched.type_name, watched.topic, show, watched.qos)
        conn.spin()
