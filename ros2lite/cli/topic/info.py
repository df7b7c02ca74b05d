"""`topic info`: type and endpoint counts of one topic; `-v` adds every endpoint's details."""

from __future__ import annotations

import click

from .. import completion, render
from ..common import connect
from ..errors import CliError
from ..options import json_option, strategy_options
from ..parsing import command


@command('info')
@strategy_options()
@click.argument('topic_name', shell_complete=completion.topics)
@click.option(
    '-v',
    '--verbose',
    is_flag=True,
    help='Also describe every publisher and subscription: node, type hash, GID and QoS',
)
@json_option(
    '{"name", "types", "publisher_count", "subscription_count"} (-v adds "publishers" and '
    '"subscriptions": node, type hash, GID, QoS)'
)
def cli(topic_name: str, verbose: bool, no_daemon: bool, use_sim_time: bool, as_json: bool) -> None:
    """Print information about a topic."""
    from ros2lite.graph import (
        EntityKind,
        count,
        endpoints_by_topic,
        format_endpoint_info,
        topic_names_and_types,
    )
    from ros2lite.names import expand_topic_name

    try:
        name = expand_topic_name(topic_name, 'ros2lite', '/')
    except ValueError as e:
        raise CliError(str(e)) from None
    with connect(no_daemon=no_daemon) as conn:
        entities = conn.entities()
    # hidden topics are always looked up here, as in ros2cli
    types = dict(topic_names_and_types(entities, include_hidden=True)).get(name)
    if types is None:
        raise CliError(f"Unknown topic '{name}'")
    if as_json:
        doc: dict[str, object] = {'name': name, 'types': types}
        for kind, key in (
            (EntityKind.PUBLISHER, 'publisher'),
            (EntityKind.SUBSCRIPTION, 'subscription'),
        ):
            doc[f'{key}_count'] = count(entities, name, kind)
            if verbose:
                doc[f'{key}s'] = [
                    render.endpoint_json(info)
                    for info in sorted(
                        endpoints_by_topic(entities, name, kind),
                        key=lambda i: (i.node_namespace, i.node_name, i.endpoint_gid),
                    )
                ]
        render.print_json(doc)
        return
    end = '\n\n' if verbose else '\n'
    out = [f'Type: {types[0] if len(types) == 1 else types}' + end]
    for kind, label in (
        (EntityKind.PUBLISHER, 'Publisher'),
        (EntityKind.SUBSCRIPTION, 'Subscription'),
    ):
        out.append(f'{label} count: {count(entities, name, kind)}' + end)
        if verbose:
            endpoints = sorted(
                endpoints_by_topic(entities, name, kind),
                key=lambda i: (i.node_namespace, i.node_name, i.endpoint_gid),
            )
            out += [format_endpoint_info(info) + end for info in endpoints]
    render.echo(''.join(out), nl=False)
