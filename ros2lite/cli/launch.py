"""`ros2lite launch <package> <file> [name:=value …]` or `ros2lite launch <path> [name:=value …]`
(ros2launch's options and messages).

The launch library does the work (:mod:`ros2lite.launch.api`); this verb parses, picks the
screen style (a colour per process on a terminal, plain text otherwise) and reports.
"""

from __future__ import annotations

import sys

import click

from . import completion
from .errors import CliError
from .options import prefix_option
from .parsing import command

# one colour per process, in order of start; launch's own warnings and errors by severity
_PALETTE = (
    'cyan',
    'green',
    'yellow',
    'magenta',
    'blue',
    'bright_cyan',
    'bright_green',
    'bright_magenta',
    'bright_blue',
    'bright_yellow',
)
_LEVELS = {'WARNING': 'yellow', 'ERROR': 'red', 'FATAL': 'red'}


class _Colours:
    """Screen style on a terminal (see cli/render.py for when)."""

    def label(self, text: str, index: int) -> str:
        return click.style(text, fg=_PALETTE[index % len(_PALETTE)], bold=True)

    def level(self, text: str, level: str) -> str:
        colour = _LEVELS.get(level)
        return click.style(text, fg=colour) if colour else text


@command(
    'launch',
    context_settings={
        # options may follow the file (`launch pkg file.py -s`); arguments are `name:=value`
        'ignore_unknown_options': True,
        'allow_interspersed_args': True,
    },
)
@click.option(
    '-n',
    '--noninteractive',
    is_flag=True,
    help='Run the launch system non-interactively, with no terminal associated',
)
@click.option('-d', '--debug', is_flag=True, help='Put the launch system in debug mode')
@click.option(
    '-p',
    '--print',
    '--print-description',
    'print_description',
    is_flag=True,
    help='Print the launch description to the console without launching it.',
)
@click.option(
    '-s',
    '--show-args',
    '--show-arguments',
    'show_args',
    is_flag=True,
    help='Show arguments that may be given to the launch file.',
)
@click.option(
    '-a',
    '--show-all-subprocesses-output',
    'show_all',
    is_flag=True,
    help='Show all launched subprocesses\' output by overriding their output configuration '
    'using the OVERRIDE_LAUNCH_PROCESS_OUTPUT envvar.',
)
@prefix_option('--launch-prefix', 'PREFIX', 'all executables', 'xterm -e gdb -ex run --args')
@click.option(
    '--launch-prefix-filter',
    metavar='REGEX',
    help='Regex pattern for filtering which executables the --launch-prefix is applied to by '
    'matching the executable name.',
)
@click.argument('package_name', shell_complete=completion.executable_packages)
@click.argument('launch_file_name', required=False, shell_complete=completion.launch_files)
@click.argument('launch_arguments', nargs=-1, type=click.UNPROCESSED)
def cli(
    noninteractive: bool,
    debug: bool,
    print_description: bool,
    show_args: bool,
    show_all: bool,
    launch_prefix: str | None,
    launch_prefix_filter: str | None,
    package_name: str,
    launch_file_name: str | None,
    launch_arguments: tuple[str, ...],
) -> None:
    """Run a launch file."""
    from pathlib import Path

    from ros2lite.launch.api import (
        find_launch_file,
        launch_a_launch_file,
        parse_launch_arguments,
    )
    from ros2lite.pkg.index import PackageIndex

    from .main import debug_enabled
    from .render import fancy

    index = PackageIndex()  # read once, for the file and for the nodes
    words = list(launch_arguments)
    notes: list[str] = []
    if launch_file_name is None or ':=' in launch_file_name:
        # single-file mode: the first argument is the launch file's path
        if launch_file_name is not None:
            words.insert(0, launch_file_name)
        path = Path(package_name)
        if not path.is_file():
            raise CliError(
                f"'{package_name}' is not a launch file: give a package and a launch file "
                'name, or the path of a launch file'
            )
    else:
        path, note = find_launch_file(package_name, launch_file_name, index)
        if note:
            notes.append(note)
    arguments = parse_launch_arguments(words)
    if print_description or show_args:
        from ros2lite.launch.introspection import describe_tree, format_arguments
        from ros2lite.launch.sources import load_launch_file

        description = load_launch_file(path.absolute())
        if print_description:
            click.echo(describe_tree(description))
        if show_args:
            click.echo(format_arguments(description))
        return
    interactive = not noninteractive and sys.stdin.isatty()
    code = launch_a_launch_file(
        path.absolute(),
        arguments,
        noninteractive=not interactive,
        debug=debug or debug_enabled(),
        launch_prefix=launch_prefix,
        launch_prefix_filter=launch_prefix_filter,
        output_override='both' if show_all else None,
        style=_Colours() if fancy() else None,
        notes=notes,
        index=index,
    )
    raise click.exceptions.Exit(code)
