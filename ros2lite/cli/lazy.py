"""A click group whose subcommands are imported only when invoked.

Help text comes from the table itself, so `ros2lite --help` imports no verb module.
"""

from __future__ import annotations

import importlib
from collections.abc import Callable
from typing import Any, TypeVar

import click

from .parsing import Group

F = TypeVar('F', bound=Callable[..., Any])


def command_group(
    package: str, doc: str, verbs: dict[str, str], *, hidden: str | None = None
) -> click.Group:
    """The `ros2lite <command>` group of the command package `package` (its `__name__`):
    `verbs` maps each verb to its one-line help, and the verb lives in module
    `<package>.<verb>`, imported only when run. Bare `<command>` prints the help.

    `hidden` ('topics', 'services') adds the group's own `--include-hidden-<hidden>` flag,
    which reaches the verbs through the context object (see `include_hidden`)."""

    @click.pass_context
    def callback(ctx: click.Context, **flags: bool) -> None:
        ctx.ensure_object(dict).update(flags)
        if ctx.invoked_subcommand is None:
            click.echo(ctx.get_help())

    callback.__doc__ = doc
    if hidden is not None:
        callback = include_hidden_option(hidden)(callback)
    lazy = {verb: (f'{package}.{verb}', summary) for verb, summary in verbs.items()}
    name = package.rpartition('.')[2]
    return click.group(name, cls=LazyGroup, lazy=lazy, invoke_without_command=True, help=doc)(
        callback
    )


def include_hidden_option(
    kind: str, verb: str | None = None, *, all_alias: bool = False
) -> Callable[[F], F]:
    """The `--include-hidden-<kind>` flag of a group or a verb (also `-a/--all` with
    `all_alias`). Its help is ros2cli's "Consider hidden <kind> as well", or with `verb`
    ('list', 'match') "Also <verb> hidden <kind> (…)"."""
    help = f'Consider hidden {kind} as well'
    if verb is not None:
        help = f"Also {verb} hidden {kind} (a name part starts with '_')"
    aliases = ('-a', '--all', f'include_hidden_{kind}') if all_alias else ()
    return click.option(f'--include-hidden-{kind}', *aliases, is_flag=True, help=help)


def include_hidden(ctx: click.Context, kind: str, flag: bool = False) -> bool:
    """`--include-hidden-<kind>` given on the verb (`flag`) or on its group (`command_group`'s
    `hidden`), whose flag reaches the verb through click's shared context object."""
    return flag or bool((ctx.obj or {}).get(f'include_hidden_{kind}'))


class LazyGroup(Group):
    """`lazy` maps a command name to ('module.path', 'one-line help'); `hidden_commands` work
    but stay out of the help. An unknown name gets the closest match (cli/suggest.py);
    the root group's `lacking` maps names ros2lite lacks on purpose to the reason."""

    def __init__(
        self,
        *args: Any,
        lazy: dict[str, tuple[str, str]] | None = None,
        hidden_commands: frozenset[str] = frozenset(),
        lacking: dict[str, str] | None = None,
        **kwargs: Any,
    ) -> None:
        super().__init__(*args, **kwargs)
        self.lazy = lazy or {}
        self.hidden_commands = hidden_commands
        self.lacking = lacking or {}

    def resolve_command(
        self, ctx: click.Context, args: list[str]
    ) -> tuple[str | None, click.Command | None, list[str]]:
        name = args[0] if args else ''
        if (
            name
            and not name.startswith('-')
            and not ctx.resilient_parsing
            and self.get_command(ctx, name) is None
        ):
            from .suggest import unknown

            shown = self.hidden_commands
            unknown(ctx, name, (n for n in self.list_commands(ctx) if n not in shown))
        return super().resolve_command(ctx, args)

    def list_commands(self, ctx: click.Context) -> list[str]:
        return sorted(set(super().list_commands(ctx)) | set(self.lazy))

    def get_command(self, ctx: click.Context, cmd_name: str) -> click.Command | None:
        if cmd_name in self.lazy:
            module = importlib.import_module(self.lazy[cmd_name][0])
            cmd: click.Command = module.cli
            return cmd
        return super().get_command(ctx, cmd_name)

    def format_commands(self, ctx: click.Context, formatter: click.HelpFormatter) -> None:
        rows = [
            (name, self.lazy[name][1])
            for name in sorted(self.lazy)
            if name not in self.hidden_commands
        ]
        rows += [(name, cmd.get_short_help_str()) for name, cmd in sorted(self.commands.items())]
        if rows:
            with formatter.section('Commands'):
                formatter.write_dl(sorted(rows))
