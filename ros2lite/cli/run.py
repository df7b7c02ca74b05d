"""`ros2lite run [--prefix CMD] <package> <executable> [argv…]` (ros2run's behaviour).

The executable runs as a child process with everything after its name passed through, so
`--ros-args -r chatter:=/x` reaches the node untouched; we wait for it and exit with its
status. The child gets the environment `ros2lite env` gives a shell, so code written for
rclpy runs as it is. Signal forwarding is the library's (:func:`ros2lite.process.run_child`).
"""

from __future__ import annotations

import shlex
import signal

import click

from . import completion
from .errors import CliError


@click.command(
    'run',
    context_settings={
        'ignore_unknown_options': True,
        'allow_interspersed_args': False,
        'help_option_names': ['-h', '--help'],
    },
)
@click.option(
    '--prefix',
    metavar='CMD',
    help="Prefix command, which should go before the executable. Command must be "
    "wrapped in quotes if it contains spaces (e.g. --prefix 'gdb -ex run --args').",
)
@click.argument('package_name', shell_complete=completion.executable_packages)
@click.argument('executable_name', shell_complete=completion.executables)
@click.argument('argv', nargs=-1, type=click.UNPROCESSED)
def cli(prefix: str | None, package_name: str, executable_name: str, argv: tuple[str, ...]) -> None:
    """Run a package specific executable."""
    import os

    from ros2lite.env import ros_environment
    from ros2lite.pkg.executables import find_executable
    from ros2lite.process import exit_code, run_child

    exe = find_executable(package_name, executable_name)  # unknown package: its own error
    if exe is None:
        raise CliError('No executable found')
    cmd = exe.command(list(argv))
    if prefix is not None:
        cmd = shlex.split(prefix) + cmd
    # the child is in a ROS shell whether or not this one is: `rclpy` and interface
    # packages import there (see `ros2lite env`)
    code = run_child(cmd, env={**os.environ, **ros_environment()})
    if code < 0:
        signum = -code
        name = signal.strsignal(signum) or f'signal {signum}'
        click.echo(f'[ros2run]: {name}', err=True)
    elif code:
        click.echo(f'[ros2run]: Process exited with failure {code}', err=True)
    raise click.exceptions.Exit(exit_code(code))
