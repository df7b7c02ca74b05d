"""`interface proto`: a default-valued YAML prototype to edit and pass to pub/call."""

from __future__ import annotations

import click

from ros2lite.interfaces.registry import default_registry
from ros2lite.interfaces.text import proto_message, proto_yaml

from .. import completion, render
from ..options import json_option
from ..parsing import command


@command('proto')
@click.argument('type_name', metavar='TYPE', shell_complete=completion.interface_types)
@click.option('--no-quotes', is_flag=True, help='if true output has no outer quotes.')
@json_option(
    'the default-valued message (a service\'s request, an action\'s goal) in the JSON form'
)
def cli(type_name: str, no_quotes: bool, as_json: bool) -> None:
    """Output an interface prototype."""
    if as_json:
        from ros2lite.interfaces.json_form import message_to_json

        render.print_json(message_to_json(proto_message(type_name, default_registry())))
        return
    text = proto_yaml(type_name, default_registry())
    click.echo(text if no_quotes else f'"{text}"')
