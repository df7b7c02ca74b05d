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

Error wording stays click's where click has a message for the case. The words are told
apart here (`_Words`), with nothing of click's private parser; click converts, defaults and
checks the values as for any command.
"""

from __future__ import annotations

import re
from collections.abc import Callable
from typing import Any, TypeVar

import click

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


class _Spelling:
    """What one spelling of an option does when it occurs: `const` is a flag's value (its
    `--no-…` spelling's False), `takes_value` False for flags and counters. (A plain class:
    dataclasses would add `inspect` to every start-up.)"""

    __slots__ = ('const', 'option', 'takes_value')

    def __init__(self, option: click.Option, takes_value: bool, const: object = None) -> None:
        self.option = option
        self.takes_value = takes_value
        self.const = const


class _Words:
    """The argparse-rules tokenizer (module doc) of one command's words, made fresh for each
    parse. It is what click's `Command.parse_args` asks `make_parser` for: `parse_args(args)`
    gives (values by parameter name, leftover words, parameters in the order they came), and
    click then converts, defaults and checks every value through its public
    `Parameter.handle_parse_result`. A value left out is a name left out of the values."""

    def __init__(self, command: click.Command, ctx: click.Context) -> None:
        self.ctx = ctx
        self.long: dict[str, _Spelling] = {}
        self.short: dict[str, _Spelling] = {}
        self.prefixes = {'-', '--'}
        self.arguments: list[click.Argument] = []
        for param in command.get_params(ctx):
            if isinstance(param, click.Argument):
                self.arguments.append(param)
            elif isinstance(param, click.Option):
                self._add(param)
        self.values: dict[str, object] = {}
        self.order: list[click.Parameter] = []
        self.rest: list[str] = []  # the words not read yet
        self.loose: list[str] = []  # the words read that are no option, in order

    @property
    def _opt_prefixes(self) -> set[str]:
        """The option prefixes: click's parse_args reads them by this name into the context,
        where its shell completion tells an option's name from a value by them."""
        return self.prefixes

    def _add(self, option: click.Option) -> None:
        if option.is_flag and option.is_bool_flag and option.secondary_opts:
            groups = [(option.opts, True), (option.secondary_opts, False)]
        else:
            groups = [(option.opts, option.flag_activation_value)]
        for spellings, const in groups:
            takes_value = not (option.is_flag or option.count)
            entry = _Spelling(option, takes_value, const if option.is_flag else None)
            for spelling in spellings:
                first = spelling[:1]
                if first.isalnum() or not first:
                    raise ValueError(f'Invalid start character for option ({spelling})')
                prefix = spelling[:2] if spelling[1:2] == first else first
                self.prefixes.add(first)
                if len(prefix) == 1 and len(spelling) == 2:
                    self.short[spelling] = entry
                else:
                    self.long[spelling] = entry
                    self.prefixes.add(prefix)

    def parse_args(self, args: list[str]) -> tuple[dict[str, Any], list[str], list[Any]]:
        """(values, leftover words, parameters in order); a usage error is raised, or with
        click's `resilient_parsing` (completion) ends the parse where it is."""
        self.rest = list(args)
        try:
            self._options()
            self._arguments()
        except click.UsageError:
            if not self.ctx.resilient_parsing:
                raise
        return self.values, self.loose, self.order

    def _is_option_word(self, arg: str) -> bool:
        """Whether argparse would read `arg` as an option (known or not) rather than a value;
        `--` counts as one (it is never a value of an option)."""
        if len(arg) < 2 or arg[:1] not in self.prefixes:
            return False
        name = arg.partition('=')[0]
        if name in self.long or name in self.short or arg[:2] in self.short:
            return True
        if arg == '--' or (arg.startswith('--') and self._candidates(name)):
            return True
        if NEGATIVE_NUMBER.fullmatch(arg) and not self._has_negative_options():
            return False
        return ' ' not in arg

    def _has_negative_options(self) -> bool:
        return any(NEGATIVE_NUMBER.fullmatch(o) for o in (*self.long, *self.short))

    def _candidates(self, prefix: str) -> list[str]:
        """The long options `prefix` abbreviates, one spelling per option."""
        seen: dict[int, str] = {}
        for name, entry in self.long.items():
            if name.startswith('--') and name.startswith(prefix):
                seen.setdefault(id(entry), name)
        return list(seen.values())

    def _options(self) -> None:
        while self.rest:
            arg = self.rest.pop(0)
            if arg == '--':
                return
            if self._is_option_word(arg):
                self._option(arg)
            elif self.ctx.allow_interspersed_args:
                self.loose.append(arg)
            else:
                self.rest.insert(0, arg)
                return

    def _option(self, arg: str) -> None:
        name, sep, value = arg.partition('=')
        explicit = value if sep else None
        if name in self.long:
            self._take(self.long[name], name, explicit)
        elif arg.startswith('--'):
            candidates = self._candidates(name)
            if len(candidates) > 1:
                raise click.BadOptionUsage(
                    name,
                    f'ambiguous option: {name} could match {", ".join(candidates)}',
                    ctx=self.ctx,
                )
            if candidates:
                self._take(self.long[candidates[0]], candidates[0], explicit)
            elif self.ctx.ignore_unknown_options:
                self.loose.append(arg)
            else:
                raise click.NoSuchOption(name, possibilities=list(self.long), ctx=self.ctx)
        elif sep and name in self.short:
            self._take(self.short[name], name, explicit)
        else:
            self._short_options(arg)

    def _short_options(self, arg: str) -> None:
        """`-abc`: flags `-a -b -c`, or the first that takes a value gets the rest (`-l5`)."""
        prefix = arg[0]
        unknown: list[str] = []
        for i, char in enumerate(arg[1:], start=2):
            name = f'{prefix}{char}'
            entry = self.short.get(name)
            if entry is None:
                if not self.ctx.ignore_unknown_options:
                    raise click.NoSuchOption(name, ctx=self.ctx)
                unknown.append(char)
                continue
            if entry.takes_value:
                self._take(entry, name, arg[i:] or None)
                break
            self._take(entry, name, None)
        if unknown:
            self.loose.append(f'{prefix}{"".join(unknown)}')

    def _take(self, entry: _Spelling, name: str, explicit: str | None) -> None:
        """Hand the option its value(s): `explicit` (`--opt=v`, `-ov`) or the next words."""
        option = entry.option
        if not entry.takes_value:
            if explicit is not None:
                raise click.BadOptionUsage(
                    name, f'Option {name!r} does not take a value.', ctx=self.ctx
                )
            self._store(entry, entry.const)  # a flag's constant or a count
            return
        if isinstance(option, Option) and option.takes_many:
            words = [explicit] if explicit is not None else self._values()
            if len(words) < option.at_least:
                raise click.BadOptionUsage(
                    name, f'Option {name!r} requires at least one argument.', ctx=self.ctx
                )
            if option.grouped:
                self._store(entry, tuple(words))
            else:
                for word in words:
                    self._store(entry, word)
            return
        if explicit is not None:
            self.rest.insert(0, explicit)
        elif option.flag_activation_value is not None:
            # a value that may be left out (argparse's nargs='?' with a const, click's
            # `flag_value` on an option that is no flag): the constant unless a value is next
            if not (self.rest and not self._is_option_word(self.rest[0])):
                self._store(entry, option.flag_activation_value)
                return
        else:
            needed = self.rest[: option.nargs]
            if len(needed) < option.nargs or any(self._is_option_word(w) for w in needed):
                raise click.BadOptionUsage(
                    name,
                    f'Option {name!r} requires an argument.'
                    if option.nargs == 1
                    else f'Option {name!r} requires {option.nargs} arguments.',
                    ctx=self.ctx,
                )
        if option.nargs == 1:
            self._store(entry, self.rest.pop(0))
        else:
            value = tuple(self.rest[: option.nargs])
            del self.rest[: option.nargs]
            self._store(entry, value)

    def _store(self, entry: _Spelling, value: object) -> None:
        """One occurrence, as click's option actions keep it: a list for `multiple`, a
        running total for `count`, else the last value."""
        option = entry.option
        name = option.name or ''
        if option.multiple:
            kept = self.values.setdefault(name, [])
            assert isinstance(kept, list)
            kept.append(value)
        elif option.count:
            count = self.values.get(name, 0)
            assert isinstance(count, int)
            self.values[name] = count + 1
        else:
            self.values[name] = value
        self.order.append(option)

    def _values(self) -> list[str]:
        """The words up to the next option or `--`, taken off the rest."""
        words: list[str] = []
        while self.rest and not self._is_option_word(self.rest[0]):
            words.append(self.rest.pop(0))
        return words

    def _arguments(self) -> None:
        """Deal the words that are no option to the positional arguments in turn; one with
        `nargs=-1` takes what the ones after it leave. A missing value stays out."""
        words = self.loose + self.rest
        counts = [a.nargs for a in self.arguments]
        star = next((i for i, n in enumerate(counts) if n < 0), len(counts))
        after = sum(counts[star + 1 :])
        head = sum(counts[:star])
        dealt: list[list[str]] = []
        taken = 0
        for n in counts[:star]:
            dealt.append(words[taken : taken + n])
            taken += n
        if star < len(counts):
            tail_start = max(taken, len(words) - after)
            dealt.append(words[taken:tail_start])
            tail = words[tail_start:]
            missing = after - len(tail)  # the missing words are the last arguments' first
            padded: list[str | None] = [None] * max(missing, 0) + list(tail)
            pos = 0
            for n in counts[star + 1 :]:
                dealt.append([w for w in padded[pos : pos + n] if w is not None])
                pos += n
            leftover: list[str] = []
        else:
            leftover = words[head:]
        for argument, got in zip(self.arguments, dealt, strict=True):
            self._argument(argument, got)
        self.loose, self.rest = leftover, []

    def _argument(self, argument: click.Argument, got: list[str]) -> None:
        if argument.nargs == 1:
            if got:
                self.values[argument.name or ''] = got[0]
        elif got:
            if 0 < argument.nargs != len(got):
                raise click.BadArgumentUsage(
                    f'Argument {argument.name!r} takes {argument.nargs} values.'
                )
            self.values[argument.name or ''] = tuple(got)
        self.order.append(argument)


class Command(click.Command):
    """A ros2lite command or verb: click's Command parsed the argparse way."""

    # click's own parse_args runs on the parser this returns; its annotation names the
    # parser click 8 keeps in its private click.parser, which _Words stands in for
    def make_parser(self, ctx: click.Context) -> _Words:  # type: ignore[override]
        return _Words(self, ctx)


class Group(click.Group, Command):
    """A ros2lite command with verbs (and the root): its own options parsed the argparse way
    (click.Group's parse_args hands the words to Command's parser), and commands made from
    it are the shared classes."""

    command_class = Command
    group_class = type


def command(name: str | None = None, **kwargs: Any) -> Callable[[Callable[..., Any]], Command]:
    """`click.command` making the shared Command (every verb is declared with it)."""
    decorate: Callable[[Callable[..., Any]], Command] = click.command(name, cls=Command, **kwargs)
    return decorate
