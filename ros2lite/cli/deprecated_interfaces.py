"""`msg` and `srv`: ros2cli's deprecated per-kind views of `interface`, kept because old
tutorials still type them. Every verb first says, on stderr, what to use instead (ros2cli's
own deprecation line), then prints what ros2msg/ros2srv printed."""

from __future__ import annotations

import click

from . import render
from .errors import CliError
from .options import json_option
from .parsing import command

_WORDS = {'msg': 'message', 'srv': 'service'}
_FLAGS = {'msg': '-m', 'srv': '-s'}


def verbs(kind: str) -> dict[str, str]:
    """The `msg`/`srv` group's verbs (`kind`) with their one-line help."""
    word = _WORDS[kind]
    return {
        'list': f'Output a list of available {word} types',
        'package': f'Output a list of available {word} types within one package',
        'packages': f'Output a list of packages which contain {kind}s',
        'show': f'Output the {word} definition',
    }


def _deprecated(kind: str, instead: str) -> None:
    click.echo(
        f"'ros2 {kind}' is deprecated and will be removed in a future ROS release. "
        f"Instead use: 'ros2 interface {instead}'",
        err=True,
    )


def _names(kind: str, package: str) -> list[str]:
    from ros2lite.interfaces.registry import default_registry

    if package not in default_registry().packages():
        raise CliError('Unknown package name')
    return [n for n in default_registry().package_interfaces(package) if n.split('/')[1] == kind]


def _print_names(names: list[str], as_json: bool) -> None:
    """Names one a line, or (`--json`) as one JSON list, as `interface package` prints them."""
    if as_json:
        render.print_json(names)
        return
    for name in names:
        click.echo(name)


def list_verb(kind: str) -> click.Command:
    """`<kind> list`: every type of that kind, sorted by package and name."""

    @command('list', help=verbs(kind)['list'] + '.')
    @json_option('["pkg/kind/Name", …]')
    def cli(as_json: bool) -> None:
        from ros2lite.interfaces import list_interfaces

        _deprecated(kind, f'list {_FLAGS[kind]}')
        _print_names([n for n in list_interfaces() if n.split('/')[1] == kind], as_json)

    return cli


def package_verb(kind: str) -> click.Command:
    """`<kind> package NAME`: the types of that kind in one package."""

    @command('package', help=verbs(kind)['package'] + '.')
    @click.argument('package_name')
    @json_option('["pkg/kind/Name", …]')
    def cli(package_name: str, as_json: bool) -> None:
        _deprecated(kind, f'package {package_name}')
        _print_names(_names(kind, package_name), as_json)

    return cli


def packages_verb(kind: str) -> click.Command:
    """`<kind> packages`: the packages that define types of that kind."""

    @command('packages', help=verbs(kind)['packages'] + '.')
    @json_option('["package", …]')
    def cli(as_json: bool) -> None:
        from ros2lite.interfaces import list_interfaces

        _deprecated(kind, f'packages {_FLAGS[kind]}')
        found = {n.split('/')[0] for n in list_interfaces() if n.split('/')[1] == kind}
        _print_names(sorted(found), as_json)

    return cli


def show_verb(kind: str) -> click.Command:
    """`<kind> show TYPE`: the definition file as written."""

    @command('show', help=verbs(kind)['show'] + '.')
    @click.argument('type_name', metavar='TYPE')
    @json_option('the parsed definition, as `interface show --json`')
    def cli(type_name: str, as_json: bool) -> None:
        from ros2lite.interfaces.registry import default_registry

        parts = type_name.split('/')
        if len(parts) == 2:
            parts = [parts[0], kind, parts[1]]
        if len(parts) != 3 or not parts[0] or not parts[2]:
            raise CliError(f'The passed {_WORDS[kind]} type is invalid')
        full = '/'.join(parts)
        _deprecated(kind, f'show {full}' + ('.srv' if kind == 'srv' else ''))
        if parts[0] not in default_registry().packages():
            raise CliError('Unknown package name')
        if full not in _names(kind, parts[0]):
            raise CliError(f'Unknown {_WORDS[kind]} name')
        if as_json:
            from ros2lite.interfaces.json_form import definition_to_json

            render.print_json(definition_to_json(full, default_registry()))
            return
        click.echo(default_registry().interface_text(full), nl=False)

    return cli
