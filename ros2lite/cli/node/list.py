"""`node list`: fully qualified node names, sorted, warning when a name is taken twice."""

from __future__ import annotations

import click

from .. import render
from ..common import connect
from ..options import json_option, strategy_options
from ..parsing import command

DUPLICATE_WARNING = (
    'WARNING: Be aware that there are nodes in the graph that share an exact '
    'name, which can have unintended side effects.'
)


@command('list')
@strategy_options()
@click.option(
    '-a', '--all', 'show_all', is_flag=True, help="Also list hidden nodes (name starts with '_')"
)
@click.option(
    '-c',
    '--count-nodes',
    '--count',
    'count_nodes',
    is_flag=True,
    help='Print only how many nodes there are',
)
@json_option('["/ns/name", …] or {"count"}')
def cli(
    show_all: bool, count_nodes: bool, no_daemon: bool, use_sim_time: bool, as_json: bool
) -> None:
    """Output a list of available nodes."""
    from ros2lite.graph import node_full_names

    with connect(no_daemon=no_daemon) as conn:
        names = node_full_names(conn.entities(), include_hidden=show_all)
    if len(set(names)) < len(names):
        click.echo(DUPLICATE_WARNING, err=True)
    if as_json:
        render.print_json({'count': len(names)} if count_nodes else names)
        return
    if count_nodes:
        click.echo(len(names))
        return
    if names:
        render.echo('\n'.join(names))
