"""`lifecycle nodes`: the managed nodes in the graph, sorted."""

from __future__ import annotations

import click

from .. import render
from ..common import connect
from ..options import count_option, json_option, strategy_options
from ..parsing import command
from .common import managed_nodes


@command('nodes')
@strategy_options()
@click.option('-a', '--all', 'show_all', is_flag=True, help='Display all nodes even hidden ones')
@count_option('nodes')
@json_option('["/node", …] or {"count"}')
def cli(
    show_all: bool, count_nodes: bool, no_daemon: bool, use_sim_time: bool, as_json: bool
) -> None:
    """Output a list of nodes with lifecycle."""
    with connect(no_daemon=no_daemon) as conn:
        names = managed_nodes(conn, show_all)
    if as_json:
        render.print_json({'count': len(names)} if count_nodes else names)
    elif count_nodes:
        click.echo(len(names))
    elif names:
        render.echo('\n'.join(names))
