"""`interface package`: the types of one package."""

from __future__ import annotations

import click

from ros2lite.interfaces.registry import default_registry

from .. import completion
from ..parsing import command


@command('package')
@click.argument('package_name', shell_complete=completion.interface_packages)
@click.option('-m', '--only-msgs', is_flag=True, help='Print out only the message types')
@click.option('-s', '--only-srvs', is_flag=True, help='Print out only the service types')
@click.option('-a', '--only-actions', is_flag=True, help='Print out only the action types')
def cli(package_name: str, only_msgs: bool, only_srvs: bool, only_actions: bool) -> None:
    """Output a list of available interface types within one package."""
    kinds = {
        k for k, flag in (('msg', only_msgs), ('srv', only_srvs), ('action', only_actions)) if flag
    } or {'msg', 'srv', 'action'}
    for name in default_registry().package_interfaces(package_name):
        if name.split('/')[1] in kinds:
            click.echo(name)
