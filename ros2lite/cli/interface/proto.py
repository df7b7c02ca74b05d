"""`interface proto`: a default-valued YAML prototype to edit and pass to pub/call."""

from __future__ import annotations

import click

from ros2lite.interfaces.registry import default_registry
from ros2lite.interfaces.text import proto_yaml

from .. import completion
from ..parsing import command


@command('proto')
@click.argument('type_name', metavar='TYPE', shell_complete=completion.interface_types)
@click.option('--no-quotes', is_flag=True, help='if true output has no outer quotes.')
def cli(type_name: str, no_quotes: bool) -> None:
    """Output an interface prototype."""
    text = proto_yaml(type_name, default_registry())
    click.echo(text if no_quotes else f'"{text}"')
