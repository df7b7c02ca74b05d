"""`interface package`: the types of one package."""

from __future__ import annotations

import click

from ros2lite.interfaces.registry import default_registry

from .. import completion, render
from ..options import json_option
from ..parsing import command


@command('package')
@click.argument('package_name', shell_complete=completion.interface_packages)
@click.option('-m', '--only-msgs', is_flag=True, help='Print out only the message types')
@click.option('-s', '--only-srvs', is_flag=True, help='Print out only the service types')
@click.option('-a', '--only-actions', is_flag=True, help='Print out only the action types')
@json_option('["pkg/kind/Name", …]')
def cli(
    package_name: str, only_msgs: bool, only_srvs: bool, only_actions: bool, as_json: bool
) -> None:
    """Output a list of available interface types within one package."""
    # ros2cli's grouping (the messages, then the services, then the actions), each group
    # sorted where ros2cli prints a set's random order; no flag is all three
    flags = (('msg', only_msgs), ('srv', only_srvs), ('action', only_actions))
    kinds = [kind for kind, flag in flags if flag] or [kind for kind, _ in flags]
    names = default_registry().package_interfaces(package_name)
    chosen = [name for kind in kinds for name in names if name.split('/')[1] == kind]
    if as_json:
        render.print_json(chosen)
        return
    for name in chosen:
        click.echo(name)
