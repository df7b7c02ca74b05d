"""`ros2lite run [--prefix CMD] <package> <executable> [argv…]` (ros2run's behaviour).

The executable runs as a child process with everything after its name passed through, so
`--ros-args -r chatter:=/x` reaches the node untouched. We wait for it and exit with its
status. Ctrl-C typed in a terminal already reaches the child (same foreground process group),
so it is forwarded only when it did not come from the terminal — a `kill -INT` or a test — or
when it is the second one; SIGTERM is always forwarded.
"""

from __future__ import annotations

import os
import shlex
import signal
import subprocess
import sys
from typing import Any

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
    from ros2lite.pkg.executables import (
        MultipleExecutablesError,
        PackageNotFoundError,
        find_executable,
    )

    try:
        exe = find_executable(package_name, executable_name)
    except (PackageNotFoundError, MultipleExecutablesError) as e:
        raise CliError(str(e)) from None
    if exe is None:
        raise CliError('No executable found')
    cmd = exe.command(list(argv))
    if prefix is not None:
        cmd = shlex.split(prefix) + cmd
    code = run_child(cmd)
    if code < 0:
        signum = -code
        name = signal.strsignal(signum) or f'signal {signum}'
        click.echo(f'[ros2run]: {name}', err=True)
        code = 128 + signum
    elif code:
        click.echo(f'[ros2run]: Process exited with failure {code}', err=True)
    raise click.exceptions.Exit(code)


def _terminal_signals_child() -> bool:
    """True when we run in the foreground of a terminal, where Ctrl-C hits the whole process
    group — the child included — so forwarding it would deliver it twice."""
    try:
        fd = os.open('/dev/tty', os.O_RDONLY | os.O_NOCTTY)
    except OSError:
        return False
    try:
        return os.tcgetpgrp(fd) == os.getpgrp()
    except OSError:
        return False
    finally:
        os.close(fd)


def run_child(cmd: list[str]) -> int:
    """Start `cmd`, forward SIGINT/SIGTERM as described above, return its returncode.

    Signals are taken by handlers installed before the child starts, not as
    KeyboardInterrupt: a Ctrl-C landing between the child's start and our wait would
    otherwise end this process early, and the terminal would hang up on the child."""
    proc: subprocess.Popen[bytes] | None = None
    interrupts = 0
    terminated = False

    def forward_int(_signum: int, _frame: Any) -> None:
        nonlocal interrupts
        interrupts += 1
        if (
            proc is not None
            and proc.poll() is None
            and (interrupts > 1 or not _terminal_signals_child())
        ):
            proc.send_signal(signal.SIGINT)

    def forward_term(signum: int, _frame: Any) -> None:
        nonlocal terminated
        terminated = True
        if proc is not None and proc.poll() is None:
            proc.send_signal(signum)

    old_int = signal.signal(signal.SIGINT, forward_int)
    old_term = signal.signal(signal.SIGTERM, forward_term)
    try:
        try:
            proc = subprocess.Popen(cmd)
        except OSError as e:
            raise CliError(f'{cmd[0]}: {e.strerror or e}') from None
        # signals that came while the child was starting (it may already run and be seen
        # running, so a SIGTERM then is no rarer than one later)
        if terminated:
            proc.send_signal(signal.SIGTERM)
        elif interrupts and not _terminal_signals_child():
            proc.send_signal(signal.SIGINT)
        return proc.wait()
    finally:
        signal.signal(signal.SIGINT, old_int)
        signal.signal(signal.SIGTERM, old_term)
        sys.stdout.flush()
