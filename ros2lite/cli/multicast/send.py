"""`multicast send`: send one `Hello World!` datagram to the multicast group."""

from __future__ import annotations

import click

from ..parsing import command
from .common import address_options


@command('send')
@address_options
@click.option(
    '--ttl',
    type=click.IntRange(0, 255),
    help='The multicast TTL (0: stays on this host; default: the system\'s, 1)',
)
def cli(group: str, port: int, interface: str | None, ttl: int | None) -> None:
    """Send a single UDP multicast packet."""
    from ros2lite.tools.multicast import check_settings, send

    check_settings(group, port, interface, ttl)
    click.echo('Sending one UDP multicast datagram...')
    send(group=group, port=port, ttl=ttl, interface=interface)
