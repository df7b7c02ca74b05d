"""`service echo`: print the introspection events of a service as they happen."""

from __future__ import annotations

from typing import TYPE_CHECKING

import click

from .. import completion
from ..common import connect, interface_type_name, resolved_name
from ..errors import CliError
from ..options import (
    NDJSON,
    format_options,
    json_option,
    qos_from_options,
    qos_options,
    strategy_options,
)
from ..parsing import command
from ..render import print_event

if TYPE_CHECKING:
    from typing_extensions import Unpack

    from ros2lite.interfaces import Message

    from ..options import MessageFormat, QosOptions


@command('echo')
@click.argument('service_name', shell_complete=completion.services)
@click.argument('service_type', required=False, shell_complete=completion.service_types)
@strategy_options()
@qos_options('services_default')
@format_options()
@json_option(f'each event in the JSON form ({NDJSON}; info.event_type as its number)')
def cli(
    service_name: str,
    service_type: str | None,
    fmt: MessageFormat,
    no_daemon: bool,
    use_sim_time: bool,
    as_json: bool,
    **qos: Unpack[QosOptions],
) -> None:
    """Echo a service.

    Prints what the service's clients and servers report on `<service>/_service_event`,
    so service introspection must be on at one of them (metadata, or contents to see the
    requests and responses).
    """
    from ros2lite.graph import EntityKind, count, service_names_and_types, topic_names_and_types
    from ros2lite.service_introspection import event_topic

    with connect(no_daemon=no_daemon, use_sim_time=use_sim_time) as conn:
        node = conn.node()
        full = resolved_name(node, service_name, 'service')
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
                'server enabled?',
                err=as_json,
            )

        def show(msg: Message) -> None:
            print_event(msg, fmt, as_json={} if as_json else None)

        # typed: a sample that is not the event type is dropped and reported, not fatal
        node.create_subscription(event_type, topic, show, qos_from_options(**qos))
        conn.spin()
