"""`action type`: the type(s) of one action; exit 1 with one line on stderr if unknown."""

from __future__ import annotations

import click

from .. import completion
from ..common import print_types_of
from ..options import json_option, strategy_options
from ..parsing import command


@command('type')
@strategy_options()
@click.argument('action_name', shell_complete=completion.actions)
@json_option('{"name", "types"}')
def cli(action_name: str, no_daemon: bool, use_sim_time: bool, as_json: bool) -> None:
    """Print a action's type."""
    from ros2lite.graph import action_names_and_types

    print_types_of(
        action_name,
        no_daemon,
        lambda entities: action_names_and_types(entities, include_hidden=True),
        'action',
        as_json,
    )
