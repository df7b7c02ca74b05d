"""`daemon stop`: stop our own router (a foreign one, e.g. rmw_zenohd, is left alone) and say
what that did to the sessions connected to it."""

from __future__ import annotations

import click

from ..errors import CliError
from ..parsing import command


@command('stop')
def cli() -> None:
    """Stop the daemon if it is running."""
    from ros2lite import daemon

    try:
        result = daemon.stop()
    except daemon.DaemonError as e:
        raise CliError(str(e)) from None
    click.echo('The daemon has been stopped' if result.stopped else 'The daemon is not running')
    if result.stopped and result.sessions is not None:
        from .common import consequences

        for line in consequences(result.sessions):
            click.echo(line)
    if result.foreign:
        click.echo(
            f'A Zenoh router not started by ros2lite answers at {result.endpoint}; not stopping it'
        )
