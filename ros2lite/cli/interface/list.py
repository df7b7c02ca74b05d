"""`interface list`: every type, grouped as ros2cli prints them."""

from __future__ import annotations

import click

from ros2lite.interfaces import list_interfaces

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
def cli(only_msgs: bool, only_srvs: bool, only_actions: bool) -> None:
    """List all interface types available."""
    chosen = [
        k for k, flag in (('msg', only_msgs), ('srv', only_srvs), ('action', only_actions)) if flag
    ]
    print_sections(chosen or ['msg', 'srv', 'action'], list_interfaces())
