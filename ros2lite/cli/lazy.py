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
    """`lazy` maps a command name to ('module.path', 'one-line help')."""

    def __init__(
        self, *args: Any, lazy: dict[str, tuple[str, str]] | None = None, **kwargs: Any
    ) -> None:
        super().__init__(*args, **kwargs)
        self.lazy = lazy or {}

    def list_commands(self, ctx: click.Context) -> list[str]:
        return sorted(set(super().list_commands(ctx)) | set(self.lazy))

    def get_command(self, ctx: click.Context, cmd_name: str) -> click.Command | None:
        if cmd_name in self.lazy:
            module = importlib.import_module(self.lazy[cmd_name][0])
            cmd: click.Command = module.cli
            return cmd
        return super().get_command(ctx, cmd_name)

    def format_commands(self, ctx: click.Context, formatter: click.HelpFormatter) -> None:
        rows = [(name, self.lazy[name][1]) for name in sorted(self.lazy)]
        rows += [(name, cmd.get_short_help_str()) for name, cmd in sorted(self.commands.items())]
        if rows:
            with formatter.section('Commands'):
                formatter.write_dl(sorted(rows))
