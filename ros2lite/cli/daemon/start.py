"""`daemon start`: run the local Zenoh router in the background (or report the one there)."""

from __future__ import annotations

import click

from ..errors import CliError
from ..parsing import command


@command('start')
@click.option(
    '-d',
    '--debug',
    is_flag=True,
    help='Print where the daemon logs (its output always goes to that file)',
)
@click.option(
    '--listen',
    metavar='ENDPOINT',
    multiple=True,
    help='Endpoint the router listens on (repeatable; default: the router endpoint, '
    'e.g. tcp/127.0.0.1:7447; use tcp/0.0.0.0:7447 to open it to the network)',
)
@click.option(
    '--connect', metavar='ENDPOINT', multiple=True, help='Another router to mesh with (repeatable)'
)
def cli(debug: bool, listen: tuple[str, ...], connect: tuple[str, ...]) -> None:
    """Start the daemon if it isn't running."""
    from ros2lite import daemon

    try:
        result = daemon.start(listen=listen, connect=connect)
    except daemon.DaemonError as e:
        raise CliError(str(e)) from None
    # the first line is ros2cli's; anything we add goes after it
    click.echo('The daemon has been started' if result.started else 'The daemon is already running')
    if result.already_running and not result.ours:
        click.echo(f'A Zenoh router not started by ros2lite answers at {result.endpoint}')
    if debug and result.log_file:
        click.echo(f'Log: {result.log_file}')
