"""Entry point of `ros2lite`: global options, the lazy command table and error handling."""

from __future__ import annotations

import contextlib
import os
import signal
import sys

import click

from ros2lite.exceptions import Ros2liteError

from . import render
from .errors import CliError
from .lazy import LazyGroup

COMMANDS: dict[str, tuple[str, str]] = {
    'action': ('ros2lite.cli.action', 'Various action related sub-commands'),
    'bag': ('ros2lite.cli.bag', 'Various rosbag related sub-commands'),
    'component': ('ros2lite.cli.component', 'Various component related sub-commands'),
    'daemon': ('ros2lite.cli.daemon', 'Various daemon related sub-commands'),
    'env': ('ros2lite.cli.env', 'Print shell lines that make this shell a ROS shell'),
    'doctor': ('ros2lite.cli.doctor', 'Check ROS setup and other potential issues'),
    'extension_points': ('ros2lite.cli.extension_points', 'List extension points'),
    'extensions': ('ros2lite.cli.extensions', 'List extensions'),
    'interface': ('ros2lite.cli.interface', 'Show information about ROS interfaces'),
    'launch': ('ros2lite.cli.launch', 'Run a launch file'),
    'lifecycle': ('ros2lite.cli.lifecycle', 'Various lifecycle related sub-commands'),
    'msg': ('ros2lite.cli.msg', 'Various msg related sub-commands'),
    'multicast': ('ros2lite.cli.multicast', 'Various multicast related sub-commands'),
    'node': ('ros2lite.cli.node', 'Various node related sub-commands'),
    'param': ('ros2lite.cli.param', 'Various param related sub-commands'),
    'pkg': ('ros2lite.cli.pkg', 'Various package related sub-commands'),
    'run': ('ros2lite.cli.run', 'Run a package specific executable'),
    'security': ('ros2lite.cli.security', 'Various security related sub-commands'),
    'service': ('ros2lite.cli.service', 'Various service related sub-commands'),
    'srv': ('ros2lite.cli.srv', 'Various srv related sub-commands'),
    'topic': ('ros2lite.cli.topic', 'Various topic related sub-commands'),
    'wtf': ('ros2lite.cli.doctor', 'Use `wtf` as alias to `doctor`'),
}

# work, but stay out of `ros2lite --help` (ros2cli hides the first two; the others are its
# deprecated aliases of `interface`)
HIDDEN = frozenset({'extension_points', 'extensions', 'msg', 'srv'})

# what ros2cli has and ros2lite does not, with the reason (one line, exit 1); 'command' or
# 'command verb'. Drop an entry when the command or verb lands.
LACKING: dict[str, str] = {
    'test': "'ros2 test' is launch_testing's runner for launch-based tests; ros2lite has no "
    'launch_testing, so run such tests with pytest',
}


def verb_tables() -> dict[str, tuple[str, dict[str, tuple[str, str]]]]:
    """ros2cli's extension group name (`ros2<command>.verb`) → (command, its verbs as
    verb → (module, help)), for every command that has verbs (imports each command's
    package, not its verbs)."""
    import importlib

    groups = {}
    for command, (module_name, _help) in COMMANDS.items():
        group = importlib.import_module(module_name).cli
        if isinstance(group, LazyGroup) and group.lazy:
            name = 'ros2cli.daemon.verb' if command == 'daemon' else f'ros2{command}.verb'
            groups[name] = (command, group.lazy)
    return groups


# set by the shell's completion hook (see cli/completion.py)
COMPLETE_VAR = '_ROS2LITE_COMPLETE'


def debug_enabled() -> bool:
    return os.environ.get('ROS2LITE_DEBUG', '') not in ('', '0', 'false', 'no')


@click.group(
    cls=LazyGroup,
    lazy=COMMANDS,
    hidden_commands=HIDDEN,
    lacking=LACKING,
    invoke_without_command=True,
    context_settings={'help_option_names': ['-h', '--help']},
)
@click.option('--debug', is_flag=True, help='Show full tracebacks on errors.')
@click.option(
    '--use-python-default-buffering',
    is_flag=True,
    help='Leave the buffering of stdout to Python (PYTHONUNBUFFERED, -u, whether stdout is a '
    'terminal) instead of writing out every line at once.',
)
@click.option(
    '--router',
    metavar='ENDPOINT',
    help='Zenoh router endpoint to use (default $ROS2LITE_ROUTER or tcp/127.0.0.1:7447).',
)
@click.version_option(package_name='ros2lite', prog_name='ros2lite')
@click.pass_context
def cli(
    ctx: click.Context, debug: bool, use_python_default_buffering: bool, router: str | None
) -> None:
    """ros2lite is an extensible command-line tool for ROS 2."""
    if not use_python_default_buffering:
        # a line printed is a line a reader of the pipe sees (ros2cli does the same)
        with contextlib.suppress(AttributeError, ValueError):
            sys.stdout.reconfigure(line_buffering=True)  # type: ignore[union-attr]
    if debug:
        os.environ['ROS2LITE_DEBUG'] = '1'
    if router:
        # every session, daemon and child process of this run reads it from here
        os.environ['ROS2LITE_ROUTER'] = router
    if ctx.invoked_subcommand is None:
        click.echo(ctx.get_help())


def main(argv: list[str] | None = None) -> int:
    """Run the CLI; returns the process exit status."""
    args = sys.argv[1:] if argv is None else argv
    instruction = os.environ.get(COMPLETE_VAR)
    if instruction:
        from click.shell_completion import shell_complete

        # the completers themselves are in cli/completion.py, attached to each argument
        return shell_complete(cli, {}, 'ros2lite', COMPLETE_VAR, instruction)
    if '--debug' in args[:1]:
        os.environ['ROS2LITE_DEBUG'] = '1'
    from ros2lite.util.process import Terminated, stop_signals_raise

    # ros2cli leaves with status 15 on SIGTERM, through rclpy's ExternalShutdownException, and
    # with 2 on SIGINT
    try:
        with stop_signals_raise():
            return _main(args)
    except Terminated:
        return signal.SIGTERM.value


def _main(args: list[str]) -> int:
    try:
        # invoke directly (not cli.main) so our handlers see every exception, including
        # BrokenPipeError, which click.main would turn into a bare exit 1
        with cli.make_context('ros2lite', list(args)) as ctx:
            rc = cli.invoke(ctx)
    except click.exceptions.Abort:
        return 2
    except click.exceptions.Exit as e:
        return e.exit_code
    except click.ClickException as e:
        e.show()
        return e.exit_code
    except KeyboardInterrupt:
        return 2
    except BrokenPipeError:
        # stdout went away (e.g. `| head`): quietly stop like other Unix tools
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        return 0
    except Ros2liteError as e:  # the library's and the CLI's own: their message is the line
        if debug_enabled():
            raise
        render.echo(str(e), err=True)  # it may name what came from outside
        return e.code if isinstance(e, CliError) else 1
    except Exception as e:  # not an error raised on purpose: a bug, said as one
        if debug_enabled():
            raise
        if _caused_by(e, KeyboardInterrupt):
            # Python 3.11 wraps a Ctrl-C that lands in a class body's __set_name__ (a lazy
            # import) in RuntimeError; it is still the user's interrupt, not a failure
            return 2
        from ros2lite.util.process import Terminated

        if _caused_by(e, Terminated):
            return signal.SIGTERM.value
        render.echo(failure_line(e), err=True)
        return 1
    return rc if isinstance(rc, int) else 0


def failure_line(error: Exception) -> str:
    """The one line an unexpected exception gets. An OSError is the machine refusing (a
    file missing, a port taken), which the user can fix, so it is said as it is; anything
    else is a bug in ros2lite and is named one, not dressed as bad input."""
    text = ' '.join(str(error).split())
    if isinstance(error, OSError):
        return text or type(error).__name__
    said = f'{type(error).__name__}: {text}' if text else type(error).__name__
    return f'ros2lite: internal error: {said} (run with --debug for the traceback)'


def _caused_by(error: BaseException, kind: type[BaseException]) -> bool:
    """Whether `kind` is anywhere in the chain of exceptions that led to `error`."""
    seen: set[int] = set()
    todo: list[BaseException] = [error]
    while todo:
        e = todo.pop()
        if id(e) in seen:
            continue
        seen.add(id(e))
        if isinstance(e, kind):
            return True
        todo.extend(x for x in (e.__cause__, e.__context__) if x is not None)
    return False


def run() -> None:
    sys.exit(main())
