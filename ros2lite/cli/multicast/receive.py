"""`multicast receive`: wait for one datagram on the multicast group and print it."""

from __future__ import annotations

import click

from .. import render
from ..errors import CliError
from ..options import json_option
from ..parsing import command
from .common import address_options


@command('receive')
@address_options
@click.option(
    '-t',
    '--timeout',
    type=click.FloatRange(min=0, min_open=True),
    metavar='N',
    help='Give up after N seconds (exit status 1; default: wait until Ctrl-C)',
)
@json_option('{"group", "port", "sender", "sender_port", "data"} of the datagram')
def cli(group: str, port: int, interface: str | None, timeout: float | None, as_json: bool) -> None:
    """Receive a single UDP multicast packet."""
    from ros2lite.tools.multicast import ZENOH_SCOUTING, check_settings, receive

    check_settings(group, port, interface)
    click.echo('Waiting for UDP multicast datagram...', err=as_json)
    try:
        data, (host, sender_port) = receive(
            group=group, port=port, timeout=timeout, interface=interface
        )
    except KeyboardInterrupt:
        return  # ros2cli ends quietly, status 0
    except TimeoutError:
        raise CliError(
            f'No UDP multicast datagram to {group}:{port} within {timeout:g} s: multicast does '
            "not pass here, so Zenoh's multicast scouting would not either (ros2lite does not "
            'need it: nodes meet through the router)'
        ) from None
    text = data.decode('utf-8', errors='replace')
    if as_json:
        render.print_json(
            {'group': group, 'port': port, 'sender': host, 'sender_port': sender_port, 'data': text}
        )
    else:
        render.echo(f"Received from {host}:{sender_port}: '{text}'")
    click.echo(
        'Multicast passes here: Zenoh peers could also find each other by multicast scouting '
        f'({ZENOH_SCOUTING}), which ros2lite and rmw_zenoh leave off (they meet through the '
        'router)',
        err=True,
    )
