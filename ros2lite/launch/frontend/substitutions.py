r"""The `$(name arg …)` substitutions of XML and YAML launch files.

Text outside `$(…)` is literal. Arguments are separated by spaces; an argument may be quoted
with `'…'` or `"…"` (to hold spaces) and may itself contain substitutions, e.g.
`$(eval '$(var x) + 1')`. `\$` is a literal dollar sign; inside quotes a backslash also
escapes a quote or a backslash. Any other backslash is kept as written.
"""

from __future__ import annotations

from collections.abc import Callable

from ..errors import InvalidFrontendLaunchFileError
from ..find_package import FindPackagePrefix, FindPackageShare
from ..substitutions import (
    AndSubstitution,
    AnonName,
    Command,
    EnvironmentVariable,
    EqualsSubstitution,
    FindExecutable,
    LaunchConfiguration,
    NotEqualsSubstitution,
    NotSubstitution,
    OrSubstitution,
    PythonExpression,
    Substitution,
    TextSubstitution,
    ThisLaunchFile,
    ThisLaunchFileDir,
)

__all__ = ['parse_substitutions']

Args = list[list[Substitution]]


def _one(name: str, args: Args, low: int, high: int) -> None:
    if not low <= len(args) <= high:
        want = str(low) if low == high else f'{low} to {high}'
        raise InvalidFrontendLaunchFileError(
            f"substitution '$({name})' takes {want} argument(s), got {len(args)}"
        )


def _fixed(
    name: str, count: int, make: Callable[..., Substitution]
) -> Callable[[Args], Substitution]:
    """A substitution that takes exactly `count` arguments, passed to `make` in order."""

    def build(args: Args) -> Substitution:
        _one(name, args, count, count)
        return make(*args)

    return build


def _var(args: Args) -> Substitution:
    _one('var', args, 1, 2)
    return LaunchConfiguration(args[0], default=args[1] if len(args) > 1 else None)


def _env(args: Args) -> Substitution:
    _one('env', args, 1, 2)
    return EnvironmentVariable(args[0], default_value=args[1] if len(args) > 1 else None)


def _optenv(args: Args) -> Substitution:
    _one('optenv', args, 1, 2)
    return EnvironmentVariable(args[0], default_value=args[1] if len(args) > 1 else '')


def _command(args: Args) -> Substitution:
    _one('command', args, 1, 2)
    mode = (
        ''.join(s.text for s in args[1] if isinstance(s, TextSubstitution))
        if len(args) > 1
        else 'fail'
    )
    return Command(args[0], on_stderr=mode)


SUBSTITUTIONS: dict[str, Callable[[Args], Substitution]] = {
    'var': _var,
    'env': _env,
    'optenv': _optenv,
    'find-pkg-share': _fixed('find-pkg-share', 1, FindPackageShare),
    'find-pkg-prefix': _fixed('find-pkg-prefix', 1, FindPackagePrefix),
    'find-exec': _fixed('find-exec', 1, lambda name: FindExecutable(name=name)),
    'dirname': _fixed('dirname', 0, ThisLaunchFileDir),
    'filename': _fixed('filename', 0, ThisLaunchFile),
    'anon': _fixed('anon', 1, AnonName),
    'eval': _fixed('eval', 1, PythonExpression),
    'command': _command,
    'not': _fixed('not', 1, NotSubstitution),
    'and': _fixed('and', 2, AndSubstitution),
    'or': _fixed('or', 2, OrSubstitution),
    'equals': _fixed('equals', 2, EqualsSubstitution),
    'not-equals': _fixed('not-equals', 2, NotEqualsSubstitution),
}


class _Parser:
    def __init__(self, text: str) -> None:
        self.text = text
        self.pos = 0

    def error(self, message: str) -> InvalidFrontendLaunchFileError:
        return InvalidFrontendLaunchFileError(f'{message} in {self.text!r} (at {self.pos})')

    def peek(self, s: str) -> bool:
        return self.text.startswith(s, self.pos)

    def top(self) -> list[Substitution]:
        """Everything: literal text and substitutions, to the end."""
        return self.fragments(stop=lambda: False)

    def fragments(self, stop: Callable[[], bool], quote: str | None = None) -> list[Substitution]:
        out: list[Substitution] = []
        buf: list[str] = []
        while self.pos < len(self.text) and not stop():
            c = self.text[self.pos]
            nxt = self.text[self.pos + 1] if self.pos + 1 < len(self.text) else ''
            if c == '\\' and (nxt == '$' or (quote is not None and nxt in '\'"\\')):
                buf.append(nxt)
                self.pos += 2
            elif self.peek('$('):
                if buf:
                    out.append(TextSubstitution(text=''.join(buf)))
                    buf = []
                out.append(self.substitution())
            elif quote is not None and c == quote:
                break
            else:
                buf.append(c)
                self.pos += 1
        if buf:
            out.append(TextSubstitution(text=''.join(buf)))
        return out

    def substitution(self) -> Substitution:
        start = self.pos
        self.pos += 2
        while self.pos < len(self.text) and self.text[self.pos] == ' ':
            self.pos += 1
        name_start = self.pos
        while self.pos < len(self.text) and (
            self.text[self.pos].isalnum() or self.text[self.pos] in '-_'
        ):
            self.pos += 1
        name = self.text[name_start : self.pos]
        args: Args = []
        while True:
            while self.pos < len(self.text) and self.text[self.pos] in ' \t\n':
                self.pos += 1
            if self.pos >= len(self.text):
                self.pos = start
                raise self.error('unterminated substitution')
            if self.text[self.pos] == ')':
                self.pos += 1
                break
            args.append(self.argument())
        maker = SUBSTITUTIONS.get(name)
        if maker is None:
            raise InvalidFrontendLaunchFileError(
                f"unknown substitution '$({name})' in {self.text!r}; known: "
                + ', '.join(sorted(SUBSTITUTIONS))
            )
        return maker(args)

    def argument(self) -> list[Substitution]:
        out: list[Substitution] = []
        while self.pos < len(self.text) and self.text[self.pos] not in ' \t\n)':
            c = self.text[self.pos]
            if c in '\'"':
                self.pos += 1
                out += self.fragments(stop=lambda: False, quote=c)
                if self.pos >= len(self.text):
                    raise self.error('unterminated quote')
                self.pos += 1  # the closing quote
            else:
                out += self.fragments(
                    stop=lambda: self.pos < len(self.text) and self.text[self.pos] in ' \t\n)\'"'
                )
        return out


def parse_substitutions(text: str) -> list[Substitution]:
    """The substitutions of a frontend string (literal text for what is not `$(…)`)."""
    if '$' not in text:
        return [TextSubstitution(text=text)]
    parts = _Parser(text).top()
    return parts or [TextSubstitution(text='')]
