"""`component unload`: unload components from a container by their unique ids."""

from __future__ import annotations

import click

from .. import completion
from ..common import connect
from ..errors import CliError
from ..options import strategy_options
from ..parsing import command
from .common import unable_to_find


@command('unload')
@click.argument('container_node_name', shell_complete=completion.nodes)
@click.argument('component_uid', nargs=-1, required=True, type=click.IntRange(min=0))
@strategy_options()
@click.option('-q', '--quiet', is_flag=True, help='Only print component unique IDs')
def cli(
    container_node_name: str,
    component_uid: tuple[int, ...],
    quiet: bool,
    no_daemon: bool,
    use_sim_time: bool,
) -> None:
    """Unload a component from a container node."""
    from ros2lite.components.remote import ContainerError, RemoteContainer, container_node_names

    with connect(no_daemon=no_daemon) as conn:
        if container_node_name not in container_node_names(conn.entities()):
            raise unable_to_find(container_node_name)
        container = RemoteContainer(conn.node(), container_node_name)
        for uid in component_uid:
            try:
                refused = container.unload(uid)
            except ContainerError as e:
                raise CliError(str(e)) from None
            if refused is not None:
                raise CliError(
                    f"Failed to unload component {uid} from '{container_node_name}' "
                    f'container node\n    {refused[:1].upper() + refused[1:]}'
                )
            if quiet:
                click.echo(uid)
            else:
                click.echo(f"Unloaded component {uid} from '{container_node_name}' container node")
