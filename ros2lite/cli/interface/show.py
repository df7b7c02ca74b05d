"""`interface show`: the definition text, nested types expanded with tabs."""

from __future__ import annotations

import sys

import click

from ros2lite.interfaces.registry import default_registry
from ros2lite.interfaces.text import show_lines

from .. import completion, render
from ..common import known_type_if_graph
from ..options import json_option
from ..parsing import command


def read_type_argument(value: str) -> str:
    """'-' reads the type name from a pipe, as in `topic type /x | interface show -`."""
    if value == '-':
        if sys.stdin is None or sys.stdin.isatty():
            raise click.UsageError('expected stdin pipe')
        value = sys.stdin.readline().strip()
    if not value:
        raise click.UsageError('the passed value is empty')
    return value


@command('show')
@click.argument('type_name', metavar='TYPE', shell_complete=completion.interface_types)
@click.option(
    '--all-comments',
    is_flag=True,
    help='Show all comments, including for nested interface definitions',
)
@click.option('--no-comments', is_flag=True, help='Show no comments or whitespace')
@json_option(
    'the parsed definition: {"name", "kind", fields/constants or its parts, "types": the '
    'nested message types}'
)
def cli(type_name: str, all_comments: bool, no_comments: bool, as_json: bool) -> None:
    """Output the interface definition (TYPE '-' reads it from stdin)."""
    if all_comments and no_comments:
        raise click.UsageError('--all-comments and --no-comments are mutually exclusive')
    name = read_type_argument(type_name)
    known_type_if_graph(name)  # a type only some node on the graph knows
    if as_json:
        from ros2lite.interfaces.json_form import definition_to_json

        render.print_json(definition_to_json(name, default_registry()))
        return
    lines = show_lines(name, default_registry(), all_comments=all_comments, no_comments=no_comments)
    click.echo(''.join(line + '\n' for line in lines), nl=False)  # an empty type: nothing
