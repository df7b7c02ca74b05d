"""`node list`: fully qualified node names, sorted, warning when a name is taken twice."""

from __future__ import annotations

import click

from .. import render
from ..common import connect
from ..options import strategy_options
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
def cli(show_all: bool, count_nodes: bool, no_daemon: bool, use_sim_time: bool) -> None:
    """Output a list of available nodes."""
    from ros2lite.graph import node_full_names

    with connect(no_daemon=no_daemon) as conn:
        names = node_full_names(conn.entities(), include_hidden=show_all)
    if count_nodes:
        click.echo(len(names))
        return
    if not names:
        return
    if len(set(names)) < len(names):
        click.echo(DUPLICATE_WARNING, err=True)
    render.echo('\n'.join(names))
