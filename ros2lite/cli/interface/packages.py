"""`interface packages`: names of packages that define interfaces."""

from __future__ import annotations

import click

from ros2lite.interfaces import list_interfaces

from .. import render
from ..options import json_option
from ..parsing import command


@command('packages')
@click.option('-m', '--only-msgs', is_flag=True, help='Only list packages that generate messages')
@click.option('-s', '--only-srvs', is_flag=True, help='Only list packages that generate services')
@click.option('-a', '--only-actions', is_flag=True, help='Only list packages that generate actions')
@json_option('["package", …]')
def cli(only_msgs: bool, only_srvs: bool, only_actions: bool, as_json: bool) -> None:
    """Output a list of packages which contain interfaces."""
    kind = 'msg' if only_msgs else 'srv' if only_srvs else 'action' if only_actions else None
    packages = {
        n.split('/')[0] for n in list_interfaces() if kind is None or n.split('/')[1] == kind
    }
    if as_json:
        render.print_json(sorted(packages))
        return
    for name in sorted(packages):
        click.echo(name)
