"""A click group whose subcommands are imported only when invoked.

Help text comes from the table itself, so `ros2lite --help` imports no verb module.
"""

from __future__ import annotations

import importlib
from typing import Any

import click


def command_group(name: str, doc: str, verbs: dict[str, tuple[str, str]]) -> click.Group:
    """A `ros2lite <name>` group of lazily imported verbs; bare `<name>` prints its help."""

    @click.pass_context
    def callback(ctx: click.Context) -> None:
        if ctx.invoked_subcommand is None:
            click.echo(ctx.get_help())

    callback.__doc__ = doc
    return click.group(name, cls=LazyGroup, lazy=verbs, invoke_without_command=True, help=doc)(
        callback
    )


class LazyGroup(click.Group):
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
