"""`component list`: the containers in the graph and the components in each."""

from __future__ import annotations

import click

from .. import completion, render
from ..common import connect
from ..errors import CliError
from ..options import json_option, strategy_options
from ..parsing import command
from .common import unable_to_find


@command('list')
@click.argument('container_node_name', required=False, shell_complete=completion.nodes)
@strategy_options()
@click.option('--containers-only', is_flag=True, help='List found containers nodes only')
@json_option('{"/container": [{"unique_id", "name"}…]} (--containers-only: empty lists)')
def cli(
    container_node_name: str | None,
    containers_only: bool,
    no_daemon: bool,
    use_sim_time: bool,
    as_json: bool,
) -> None:
    """Output a list of running containers and components."""
    from ros2lite.components.remote import (
        LIST_TIMEOUT,
        ContainerError,
        RemoteContainer,
        container_node_names,
    )

    with connect(no_daemon=no_daemon) as conn:
        containers = container_node_names(conn.entities())
        if container_node_name is not None:
            if container_node_name not in containers:
                raise unable_to_find(container_node_name)
            containers, indent, heading = [container_node_name], '', False
        else:
            indent, heading = '  ', True
        doc: dict[str, list[dict[str, object]]] = {}
        for name in containers:
            doc[name] = []
            if heading and not as_json:
                render.echo(name)
            if containers_only:
                continue
            try:
                loaded = RemoteContainer(conn.node(), name, LIST_TIMEOUT).list_nodes()
            except ContainerError as e:
                raise CliError(str(e)) from None
            if as_json:
                doc[name] = [{'unique_id': c.unique_id, 'name': c.name} for c in loaded]
                continue
            for component in loaded:
                render.echo(f'{indent}{component.unique_id}  {component.name}')
    if as_json:
        render.print_json(doc)
