"""`action list`: the actions in the graph (servers and clients alike)."""

from __future__ import annotations

from ..common import connect
from ..lazy import include_hidden_option
from ..options import count_option, json_option, show_types_option, strategy_options
from ..parsing import command
from ..render import print_names


@command('list')
@strategy_options()
@show_types_option('action')
@count_option('actions')
@include_hidden_option('actions', 'list', all_alias=True)
@json_option('[{"name", "types"}…] or {"count"}')
def cli(
    show_types: bool,
    count_actions: bool,
    include_hidden_actions: bool,
    no_daemon: bool,
    use_sim_time: bool,
    as_json: bool,
) -> None:
    """Output a list of action names."""
    from ros2lite.graph import action_names_and_types

    with connect(no_daemon=no_daemon) as conn:
        entities = conn.entities()
    print_names(
        action_names_and_types(entities, include_hidden_actions), count_actions, show_types, as_json
    )
