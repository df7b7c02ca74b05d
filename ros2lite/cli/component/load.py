"""`component load`: load a component into a running container."""

from __future__ import annotations

from typing import Any

import click

from .. import completion
from ..common import connect
from ..options import strategy_options
from ..parsing import command
from .common import component_options, load, unable_to_find


@command('load')
@click.argument('container_node_name', shell_complete=completion.nodes)
@component_options
@strategy_options()
@click.option('-q', '--quiet', is_flag=True, help='Only print the unique ID of the component')
def cli(
    container_node_name: str, quiet: bool, no_daemon: bool, use_sim_time: bool, **options: Any
) -> None:
    """Load a component into a container node.

    PACKAGE_NAME is the package where the component is found, PLUGIN_NAME its type name
    (e.g. `composition composition::Talker`; see `component types`).
    """
    from ros2lite.components.remote import container_node_names

    with connect(no_daemon=no_daemon) as conn:
        if container_node_name not in container_node_names(conn.entities()):
            raise unable_to_find(container_node_name)
        loaded = load(conn, container_node_name, options)
    if quiet:
        click.echo(loaded.unique_id)
    else:
        click.echo(
            f"Loaded component {loaded.unique_id} into '{container_node_name}' "
            f"container node as '{loaded.name}'"
        )
