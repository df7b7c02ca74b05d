"""The one place ros2lite's commands parse their words: click's Command, Group and Option,
with a parser that keeps the habits of ros2cli's argparse that hands and scripts rely on.

- A word is an option when argparse would take it for one: a known option (also with
  `=value`), an unambiguous prefix of a long option (`--include-warning`), or any other word
  starting with `-` but a negative number (`-5`, `-1.5`, `-1e-3`: values, unless the
  command has an option spelled like one, as `topic pub -1`) or a word with a space in it.
- An option taking a value never takes an option as its value (`-o --all` is a usage error);
  a negative number is a value (`-r -1`).
- `ManyValues` takes every following word up to the next option or `--` (argparse's
  `nargs='+'`), so positionals may follow it after another option.
- An ambiguous prefix is a usage error naming the candidates (exit 2).
- Options may follow positionals; `--` ends the options.

Error wording stays click's where click has a message for the case.
"""

from __future__ import annotations

import re
from collections.abc import Callable
from typing import Any, TypeVar

import click
from click.parser import _Option, _OptionParser, _ParsingState

F = TypeVar('F', bound=Callable[..., Any])

# a negative number: argparse's (`-5`, `-1.5`, `-.5`) and the other words float() reads
# (`-1e-3`, `-inf`), which argparse refuses as unknown options, so no ros2cli line changes
NEGATIVE_NUMBER = re.compile(
    r'-(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?|-(inf|infinity|nan)', re.IGNORECASE
)


class Option(click.Option):
    """click's Option as every ros2lite command declares it; subclasses say how many words
    an occurrence takes."""

    takes_many = False  # one word per occurrence (or click's fixed `nargs`)
    grouped = False  # with takes_many: each occurrence one tuple, not word by word
    at_least = 1  # with takes_many: the fewest words an occurrence takes


class ManyValues(Option):
    """An option taking one or more words, up to the next option (argparse's `nargs='+'`;
    `at_least=0`: `nargs='*'`): `--topics /a /b -o out`. Repeating it adds to the list."""

    takes_many = True

    def __init__(self, *args: Any, at_least: int = 1, **kwargs: Any) -> None:
        kwargs.setdefault('multiple', True)
        super().__init__(*args, **kwargs)
        self.at_least = at_least


class ValueGroups(ManyValues):
    """Like ManyValues, but each occurrence stays one tuple: `-i a mcap -i b` gives
    (('a', 'mcap'), ('b',)), argparse's `action='append', nargs='+'`."""

    grouped = True

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        kwargs.setdefault('type', click.UNPROCESSED)
        super().__init__(*args, **kwargs)


class _Parser(_OptionParser):
    """click's parser with argparse's rules for telling options from values (module doc)."""

    def _is_option_word(self, arg: str) -> bool:
        """Whether argparse would read `arg` as an option (known or not) rather than a value;
        `--` counts as one (it is never a value of an option)."""
        if len(arg) < 2 or arg[:1] not in self._opt_prefixes:
            return False
        name = arg.partition('=')[0]
        if name in self._long_opt or name in self._short_opt or arg[:2] in self._short_opt:
            return True
        if arg == '--' or (arg.startswith('--') and self._candidates(name)):
            return True
        if NEGATIVE_NUMBER.fullmatch(arg) and not self._has_negative_options():
            return False
        return ' ' not in arg

    def _has_negative_options(self) -> bool:
        return any(NEGATIVE_NUMBER.fullmatch(o) for o in (*self._long_opt, *self._short_opt))

    def _candidates(self, prefix: str) -> list[str]:
        """The long options `prefix` abbreviates, one spelling per option."""
        seen: dict[int, str] = {}
        for name in self._long_opt:
            if name.startswith('--') and name.startswith(prefix):
                seen.setdefault(id(self._long_opt[name]), name)
        return list(seen.values())

    def _process_args_for_options(self, state: _ParsingState) -> None:
        while state.rargs:
            arg = state.rargs.pop(0)
            if arg == '--':
                return
            if self._is_option_word(arg):
                self._process_opts(arg, state)
            elif self.allow_interspersed_args:
                state.largs.append(arg)
            else:
                state.rargs.insert(0, arg)
                return

    def _process_opts(self, arg: str, state: _ParsingState) -> None:
        name, sep, value = arg.partition('=')
        explicit = value if sep else None
        if name in self._long_opt:
            self._take(self._long_opt[name], name, explicit, state)
        elif arg.startswith('--'):
            candidates = self._candidates(name)
            if len(candidates) > 1:
                raise click.BadOptionUsage(
                    name,
                    f'ambiguous option: {name} could match {", ".join(candidates)}',
                    ctx=self.ctx,
                )
            if candidates:
                self._take(self._long_opt[candidates[0]], candidates[0], explicit, state)
            elif self.ignore_unknown_options:
                state.largs.append(arg)
            else:
                raise click.NoSuchOption(name, possibilities=list(self._long_opt), ctx=self.ctx)
        elif sep and name in self._short_opt:
            self._take(self._short_opt[name], name, explicit, state)
        else:
            self._match_short_opt(arg, state)

    def _match_short_opt(self, arg: str, state: _ParsingState) -> None:
        """`-abc`: flags `-a -b -c`, or the first that takes a value gets the rest (`-l5`)."""
        prefix = arg[0]
        unknown: list[str] = []
        for i, char in enumerate(arg[1:], start=2):
            name = f'{prefix}{char}'
            option = self._short_opt.get(name)
            if option is None:
                if not self.ignore_unknown_options:
                    raise click.NoSuchOption(name, ctx=self.ctx)
                unknown.append(char)
                continue
            if option.takes_value:
                self._take(option, name, arg[i:] or None, state)
                break
            self._take(option, name, None, state)
        if unknown:
            state.largs.append(f'{prefix}{"".join(unknown)}')

    def _take(self, option: _Option, name: str, explicit: str | None, state: _ParsingState) -> None:
        """Hand `option` its value(s): `explicit` (`--opt=v`, `-ov`) or the next words."""
        if not option.takes_value:
            if explicit is not None:
                raise click.BadOptionUsage(
                    name, f'Option {name!r} does not take a value.', ctx=self.ctx
                )
            option.process(None, state)  # a flag's constant or count: no value to pass
            return
        obj = option.obj
        if isinstance(obj, Option) and obj.takes_many:
            words = [explicit] if explicit is not None else self._values(state)
            if len(words) < obj.at_least:
                raise click.BadOptionUsage(
                    name, f'Option {name!r} requires at least one argument.', ctx=self.ctx
                )
            if obj.grouped:
                option.process(tuple(words), state)
            else:
                for word in words:
                    option.process(word, state)
            return
        if explicit is not None:
            state.rargs.insert(0, explicit)
        elif getattr(obj, '_flag_needs_value', False):
            # an option whose value may be left out (argparse's nargs='?' with a const):
            # click decides, once a value-looking word is not next
            if not (state.rargs and not self._is_option_word(state.rargs[0])):
                option.process(self._get_value_from_state(name, option, state), state)
                return
        else:
            needed = state.rargs[: option.nargs]
            if len(needed) < option.nargs or any(self._is_option_word(w) for w in needed):
                raise click.BadOptionUsage(
                    name,
                    f'Option {name!r} requires an argument.'
                    if option.nargs == 1
                    else f'Option {name!r} requires {option.nargs} arguments.',
                    ctx=self.ctx,
                )
        if option.nargs == 1:
            option.process(state.rargs.pop(0), state)
        else:
            value = tuple(state.rargs[: option.nargs])
            del state.rargs[: option.nargs]
            option.process(value, state)

    def _values(self, state: _ParsingState) -> list[str]:
        """The words up to the next option or `--`, taken off `state`."""
        words: list[str] = []
        while state.rargs and not self._is_option_word(state.rargs[0]):
            words.append(state.rargs.pop(0))
        return words


def _parser(command: click.Command, ctx: click.Context) -> _OptionParser:
    parser = _Parser(ctx)
    for param in command.get_params(ctx):
        param.add_to_parser(parser, ctx)
    return parser


class Command(click.Command):
    """A ros2lite command or verb: click's Command parsed the argparse way."""

    def make_parser(self, ctx: click.Context) -> _OptionParser:
        return _parser(self, ctx)


class Group(click.Group):
    """A ros2lite command with verbs (and the root): its own options parsed the argparse way,
    and commands made from it are the shared classes."""

    command_class = Command
    group_class = type

    def make_parser(self, ctx: click.Context) -> _OptionParser:
        return _parser(self, ctx)


def command(name: str | None = None, **kwargs: Any) -> Callable[[Callable[..., Any]], Command]:
    """`click.command` making the shared Command (every verb is declared with it)."""
    decorate: Callable[[Callable[..., Any]], Command] = click.command(name, cls=Command, **kwargs)
    return decorate
