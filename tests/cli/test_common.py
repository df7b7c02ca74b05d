"""The option blocks the verbs share (cli/common.py), on a bare click command: what the
verb receives, and what the help lists in which order."""

from __future__ import annotations

import json

import click
from click.testing import CliRunner

from ros2lite.cli.common import MessageFormat, format_options


@click.command()
@click.argument('name')
@format_options(after_csv=[click.option('--field')])
@click.option('--once', is_flag=True)
def echo(name: str, fmt: MessageFormat, field: str | None, once: bool) -> None:
    click.echo(json.dumps({'name': name, 'fmt': fmt, 'field': field, 'once': once}))


def test_format_options_reach_the_verb_as_one_argument() -> None:
    runner = CliRunner()
    plain = json.loads(runner.invoke(echo, ['x']).output)
    assert plain == {
        'name': 'x',
        'fmt': {
            'csv': False,
            'flow_style': False,
            'truncate_length': 128,
            'no_arr': False,
            'no_str': False,
        },
        'field': None,
        'once': False,
    }
    args = ['x', '--csv', '--flow-style', '--no-arr', '--no-str', '-l', '3', '--field', 'a']
    given = json.loads(runner.invoke(echo, [*args, '--once']).output)
    assert given['fmt'] == {
        'csv': True,
        'flow_style': True,
        'truncate_length': 3,
        'no_arr': True,
        'no_str': True,
    }
    assert (given['field'], given['once']) == ('a', True)
    # --full-length wins over any truncation
    full = json.loads(runner.invoke(echo, ['x', '-l', '3', '-f']).output)
    assert full['fmt']['truncate_length'] is None


def test_format_options_refuse_a_negative_length_and_keep_their_order() -> None:
    runner = CliRunner()
    bad = runner.invoke(echo, ['x', '-l', '-1'])
    assert bad.exit_code == 2 and "Invalid value for '-l' / '--truncate-length'" in bad.output
    flags = [
        line.split()[0].rstrip(',')
        for line in runner.invoke(echo, ['--help']).output.splitlines()
        if line.startswith('  -')
    ]
    assert flags == [
        '--csv',
        '--field',
        '-f',
        '-l',
        '--no-arr',
        '--no-str',
        '--flow-style',
        '--once',
        '--help',
    ]
