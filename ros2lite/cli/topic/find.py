"""`topic find`: the topics that carry one exact type."""

from __future__ import annotations

import click

from .. import completion
from ..common import print_names_of_type
from ..lazy import include_hidden, include_hidden_option
from ..options import json_option, strategy_options
from ..parsing import command


@command('find')
@strategy_options()
@click.argument('topic_type', shell_complete=completion.message_types)
@click.option('-c', '--count-topics', is_flag=True, help='Print only how many topics match')
@include_hidden_option('topics', 'match')
@click.pass_context
@json_option('[{"name", "types"}…] or {"count"}')
def cli(
    ctx: click.Context,
    topic_type: str,
    count_topics: bool,
    include_hidden_topics: bool,
    no_daemon: bool,
    use_sim_time: bool,
    as_json: bool,
) -> None:
    """Output a list of available topics of a given type."""
    from ros2lite.graph import topic_names_and_types

    print_names_of_type(
        topic_type,
        count_topics,
        no_daemon,
        lambda entities: topic_names_and_types(
            entities, include_hidden(ctx, 'topics', include_hidden_topics)
        ),
        as_json,
    )
