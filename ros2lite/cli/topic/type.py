"""`topic type`: the type(s) of one topic; like ros2cli it fails silently (exit 1) if unknown."""

from __future__ import annotations

import click

from .. import completion
from ..common import print_types_of
from ..lazy import include_hidden
from ..options import json_option, strategy_options
from ..parsing import command


@command('type')
@strategy_options()
@click.argument('topic_name', shell_complete=completion.topics)
@click.pass_context
@json_option('{"name", "types"}')
def cli(
    ctx: click.Context, topic_name: str, no_daemon: bool, use_sim_time: bool, as_json: bool
) -> None:
    """Print a topic's type."""
    from ros2lite.graph import topic_names_and_types

    print_types_of(
        topic_name,
        no_daemon,
        lambda entities: topic_names_and_types(entities, include_hidden(ctx, 'topics')),
        as_json=as_json,
    )
