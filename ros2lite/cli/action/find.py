"""`action find`: the actions of one exact type."""

from __future__ import annotations

import click

from .. import completion
from ..common import print_names_of_type
from ..lazy import include_hidden_option
from ..options import count_option, json_option, strategy_options
from ..parsing import command


@command('find')
@strategy_options()
@click.argument('action_type', shell_complete=completion.action_types)
@count_option('actions')
@include_hidden_option('actions', 'match', all_alias=True)
@json_option('[{"name", "types"}…] or {"count"}')
def cli(
    action_type: str,
    count_actions: bool,
    include_hidden_actions: bool,
    no_daemon: bool,
    use_sim_time: bool,
    as_json: bool,
) -> None:
    """Find actions from type."""
    from ros2lite.graph import action_names_and_types

    print_names_of_type(
        action_type,
        count_actions,
        no_daemon,
        lambda entities: action_names_and_types(entities, include_hidden_actions),
        as_json,
    )
