"""`topic list`: the topics in the graph, optionally with types or per-direction counts."""

from __future__ import annotations

import click

from .. import render
from ..common import connect
from ..lazy import include_hidden, include_hidden_option
from ..options import json_option, strategy_options
from ..parsing import command
from ..render import print_names


def _section(rows: list[tuple[str, list[str], int]], publishers: bool) -> str:
    """ros2cli's `-v` block: heading, one ` * ` line per topic with endpoints, blank line."""
    what = 'publisher' if publishers else 'subscriber'
    lines = [('Published' if publishers else 'Subscribed') + ' topics:']
    lines += [
        f' * {name} [{", ".join(types)}] {n} {what}{"s" if n > 1 else ""}'
        for name, types, n in rows
        if n
    ]
    return '\n'.join(lines) + '\n'


@command('list')
@strategy_options()
@click.option('-t', '--show-types', is_flag=True, help="Also print each topic's type(s)")
@click.option(
    '-c',
    '--count-topics',
    '--count',
    'count_topics',
    is_flag=True,
    help='Print only how many topics there are',
)
@include_hidden_option('topics', 'list', all_alias=True)
@click.option('-v', '--verbose', is_flag=True, help='Count publishers and subscribers per topic')
@json_option('[{"name", "types"}…] (-v adds publisher_count, subscription_count)')
@click.pass_context
def cli(
    ctx: click.Context,
    show_types: bool,
    count_topics: bool,
    include_hidden_topics: bool,
    verbose: bool,
    no_daemon: bool,
    use_sim_time: bool,
    as_json: bool,
) -> None:
    """Output a list of available topics."""
    from ros2lite.graph import topic_counts, topic_names_and_types

    with connect(no_daemon=no_daemon) as conn:
        entities = conn.entities()
    topics = topic_names_and_types(entities, include_hidden(ctx, 'topics', include_hidden_topics))
    if as_json and verbose and not count_topics:
        counts = topic_counts(entities)
        render.print_json(
            [
                {
                    'name': name,
                    'types': types,
                    'publisher_count': counts[name][0],
                    'subscription_count': counts[name][1],
                }
                for name, types in topics
            ]
        )
        return
    if verbose and topics and not count_topics and not as_json:
        counts = topic_counts(entities)
        pubs = [(name, types, counts[name][0]) for name, types in topics]
        subs = [(name, types, counts[name][1]) for name, types in topics]
        render.echo(_section(pubs, True))
        render.echo(_section(subs, False))
        return
    print_names(topics, count_topics, show_types, as_json)
