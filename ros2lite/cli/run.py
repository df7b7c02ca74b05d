"""`ros2lite run [--prefix CMD] <package> <executable> [argv…]` (ros2run's behaviour).

The executable runs as a child process with everything after its name passed through, so
`--ros-args -r chatter:=/x` reaches the node untouched; we wait for it and exit with its
status. Finding it is the package index's (:func:`ros2lite.pkg.executables.resolve_executable`,
source workspaces included); the child gets the environment `ros2lite env` gives a shell, so
code written for rclpy runs as it is; signal forwarding is the library's
(:func:`ros2lite.util.process.run_child`).
"""

from __future__ import annotations

import shlex
import signal

import click

from . import completion
from .options import prefix_option
from .parsing import command


@command(
    'run',
    context_settings={
        'ignore_unknown_options': True,
        'allow_interspersed_args': False,
    },
)
@prefix_option('--prefix', 'CMD', 'the executable', 'gdb -ex run --args')
@click.argument('package_name', shell_complete=completion.executable_packages)
@click.argument('executable_name', shell_complete=completion.executables)
@click.argument('argv', nargs=-1, type=click.UNPROCESSED)
def cli(prefix: str | None, package_name: str, executable_name: str, argv: tuple[str, ...]) -> None:
    """Run a package specific executable."""
    from ros2lite.pkg.environment import child_environment
    from ros2lite.pkg.executables import resolve_executable
    from ros2lite.pkg.index import PackageIndex
    from ros2lite.util.process import exit_code, run_child

    index = PackageIndex()
    resolved = resolve_executable(package_name, executable_name, index=index)
    if resolved.note:
        click.echo(f'[ros2run]: {resolved.note}', err=True)
    exe = resolved.executable
    cmd = exe.prefixed_command(shlex.split(prefix or ''), list(argv))
    env = child_environment(pythonpath=exe.pythonpath, workspaces=index.workspaces())
    # a Python target runs through the runner, which takes a Ctrl-C of its start-up late
    code = run_child(cmd, env=env, hold_interrupts=exe.is_python and not prefix)
    if code < 0:
        signum = -code
        name = signal.strsignal(signum) or f'signal {signum}'
        click.echo(f'[ros2run]: {name}', err=True)
    elif code:
        click.echo(f'[ros2run]: Process exited with failure {code}', err=True)
    raise click.exceptions.Exit(exit_code(code))
