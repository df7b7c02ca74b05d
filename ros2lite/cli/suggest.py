"""What an unknown command or verb gets: the closest name, every name that exists, or — for
one ros2lite lacks on purpose — one line saying why."""

from __future__ import annotations

import difflib
from collections.abc import Iterable

import click

from .errors import CliError


def closest(name: str, known: Iterable[str]) -> str | None:
    """The known name `name` most likely stands for: a close spelling, else the one name it
    is a prefix of."""
    names = sorted(set(known))
    match = difflib.get_close_matches(name, names, n=1, cutoff=0.6)
    if match:
        return match[0]
    prefixed = [n for n in names if n.startswith(name)]
    return prefixed[0] if len(prefixed) == 1 and name else None


def unknown(ctx: click.Context, name: str, known: Iterable[str]) -> None:
    """Fail for `name`, unknown in `ctx`'s group: exit 1 with the reason if ros2lite lacks
    it on purpose (the root group's `lacking` table, keyed 'command' or 'command verb'),
    else a usage error (exit 2) naming the closest match and the choices."""
    path = ctx.command_path.split()[1:]  # without the program name
    key = ' '.join([*path, name])
    lacking = getattr(ctx.find_root().command, 'lacking', {})
    if key in lacking:
        raise CliError(lacking[key])
    names = sorted(set(known))
    what = 'verb' if path else 'command'
    where = f" of '{' '.join(path)}'" if path else ''
    hint = closest(name, names)
    guess = f" Did you mean '{hint}'?" if hint else ''
    ctx.fail(f"No such {what} '{name}'{where}.{guess} (choose from {', '.join(names)})")
