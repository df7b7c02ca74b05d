"""`interface list`: every type, grouped as ros2cli prints them."""

from __future__ import annotations

import click

from ros2lite.interfaces import list_interfaces

from .. import render
from ..options import json_option
from ..parsing import command

_SECTIONS = (('msg', 'Messages:'), ('srv', 'Services:'), ('action', 'Actions:'))


def print_sections(kinds: list[str], names: list[str]) -> None:
    for kind, title in _SECTIONS:
        if kind in kinds:
            click.echo(title)
            for name in names:
                if name.split('/')[1] == kind:
                    click.echo(f'    {name}')


@command('list')
@click.option('-m', '--only-msgs', is_flag=True, help='Print out only the message types')
@click.option('-s', '--only-srvs', is_flag=True, help='Print out only the service types')
@click.option('-a', '--only-actions', is_flag=True, help='Print out only the action types')
@json_option('{"messages", "services", "actions"}: lists of type names (the kinds asked for)')
def cli(only_msgs: bool, only_srvs: bool, only_actions: bool, as_json: bool) -> None:
    """List all interface types available."""
    chosen = [
        k for k, flag in (('msg', only_msgs), ('srv', only_srvs), ('action', only_actions)) if flag
    ]
    kinds = chosen or ['msg', 'srv', 'action']
    if as_json:
        names = list_interfaces()
        keys = {'msg': 'messages', 'srv': 'services', 'action': 'actions'}
        render.print_json(
            {
                keys[k]: [n for n in names if n.split('/')[1] == k]
                for k, _ in _SECTIONS
                if k in kinds
            }
        )
        return
    print_sections(kinds, list_interfaces())
