"""`action list`: the actions in the graph (servers and clients alike)."""

from __future__ import annotations

import click

from ..common import connect, print_names, strategy_options


@click.command('list')
@strategy_options()
@click.option('-t', '--show-types', is_flag=True, help='Additionally show the action type')
@click.option(
    '-c', '--count-actions', is_flag=True, help='Only display the number of actions discovered'
)
@click.option(
    '--include-hidden-actions',
    '-a',
    '--all',
    'include_hidden_actions',
    is_flag=True,
    help="Also list hidden actions (a name part starts with '_')",
)
def cli(
    show_types: bool,
    count_actions: bool,
    include_hidden_actions: bool,
    no_daemon: bool,
    use_sim_time: bool,
) -> None:
    """Output a list of action names."""
    from ros2lite.graph import action_names_and_types

    with connect(no_daemon=no_daemon) as conn:
        entities = conn.entities()
    print_names(action_names_and_types(entities, include_hidden_actions), count_actions, show_types)
