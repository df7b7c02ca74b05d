"""`service echo`: print the introspection events of a service as they happen."""

from __future__ import annotations

import sys
from typing import TYPE_CHECKING

import click

from .. import completion
from ..common import connect, interface_type_name, qos_from_options, qos_options, strategy_options
from ..errors import CliError

if TYPE_CHECKING:
    from typing_extensions import Unpack

    from ros2lite.subscription import MessageInfo

    from ..common import QosOptions

DEFAULT_TRUNCATE_LENGTH = 128


@click.command('echo')
@click.argument('service_name', shell_complete=completion.services)
@click.argument('service_type', required=False, shell_complete=completion.service_types)
@strategy_options()
@qos_options('services_default')
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
    service_name: str,
    service_type: str | None,
    csv: bool,
    full_length: bool,
    truncate_length: int,
    no_arr: bool,
    no_str: bool,
    flow_style: bool,
    no_daemon: bool,
    use_sim_time: bool,
    **qos: Unpack[QosOptions],
) -> None:
    """Echo a service.

    Prints what the service's clients and servers report on `<service>/_service_event`,
    so service introspection must be on at one of them (metadata, or contents to see the
    requests and responses).
    """
    from ros2lite.graph import EntityKind, count, service_names_and_types, topic_names_and_types
    from ros2lite.interfaces import deserialize
    from ros2lite.service_introspection import event_topic, format_event

    with connect(no_daemon=no_daemon, use_sim_time=use_sim_time) as conn:
        node = conn.node()
        try:
            full = node.resolve_service_name(service_name)
        except ValueError:
            raise CliError(f"The service name '{service_name}' is invalid") from None
        topic = event_topic(full)
        entities = conn.entities()
        if service_type is not None:
            type_name = interface_type_name(
                service_type, 'srv', invalid=f"The service type '{service_type}' is invalid"
            )
        else:
            # the service's own type, else what its event topic carries (`<Srv>_Event`)
            types = dict(service_names_and_types(entities, include_hidden=True)).get(full) or [
                t.removesuffix('_Event')
                for t in dict(topic_names_and_types(entities, True)).get(topic, [])
            ]
            if not types:
                raise CliError('Could not load the type for the passed service')
            type_name = types[0]
        event_type = f'{type_name}_Event'
        if not count(entities, topic, EntityKind.PUBLISHER):
            click.echo(
                f"No publishers on topic '{topic}'; is service introspection on the client or "
                'server enabled?'
            )

        def show(data: bytes, _info: MessageInfo) -> None:
            text = format_event(
                deserialize(event_type, data),
                csv=csv,
                flow_style=flow_style,
                truncate_length=None if full_length else truncate_length,
                no_arr=no_arr,
                no_str=no_str,
            )
            sys.stdout.write(text + ('\n' if csv else '---\n'))

        node.create_subscription(event_type, topic, show, qos_from_options(**qos), raw=True)
        conn.spin()
