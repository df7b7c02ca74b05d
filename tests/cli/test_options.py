"""The option blocks the verbs share (cli/options.py), on a bare click command: what the
verb receives, and what the help lists in which order."""

from __future__ import annotations

import dataclasses
import json
from typing import Any

import click
from click.testing import CliRunner

from ros2lite.bag.player import PlayOptions
from ros2lite.cli.bag.play import cli as bag_play
from ros2lite.cli.options import (
    MessageFormat,
    bind,
    format_options,
    qos_from_options,
    qos_options,
)
from ros2lite.cli.parsing import ManyValues, command


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


@click.command()
@qos_options('sensor_data')
def subscribe(**qos: Any) -> None:
    profile = qos_from_options(**qos)
    click.echo(
        ' '.join(
            str(v)
            for v in (
                profile.history.short_key,
                profile.depth,
                profile.reliability.short_key,
                profile.durability.short_key,
                profile.liveliness.short_key,
                profile.liveliness_lease_duration.nanoseconds,
            )
        )
    )


def test_qos_options_build_the_profile_from_the_preset() -> None:
    runner = CliRunner()
    # the preset as it is: sensor_data is keep_last 5, best effort, volatile
    assert runner.invoke(subscribe, []).output.split()[:4] == [
        'keep_last',
        '5',
        'best_effort',
        'volatile',
    ]
    args = ['--qos-history', 'keep_all', '--qos-reliability', 'reliable']
    args += ['--qos-durability', 'transient_local', '--qos-liveliness', 'manual_by_topic']
    args += ['--qos-liveliness-lease-duration-seconds', '1.5', '--qos-depth', '7']
    assert runner.invoke(subscribe, args).output == (
        'keep_all 7 reliable transient_local manual_by_topic 1500000000\n'
    )


def test_qos_options_offer_ros2cli_choices_only() -> None:
    refused = CliRunner().invoke(subscribe, ['--qos-liveliness', 'manual_by_node'])
    assert refused.exit_code == 2
    assert (
        "'system_default', 'automatic', 'manual_by_topic', 'unknown', 'best_available'"
        in refused.output
    )


@dataclasses.dataclass
class Settings:
    name: str
    topics: list[str] = dataclasses.field(default_factory=list)
    rate: float = 1.0
    quiet: bool = False


loads: list[type[Settings]] = []


def load_settings() -> type[Settings]:
    loads.append(Settings)
    return Settings


@command('configure')
@click.argument('name')
@click.option('--topics', cls=ManyValues)
@click.option('--rate', type=float)
@click.option('--node-name', default='n')
@bind(load_settings, 'settings')
def configure(settings: Settings, node_name: str) -> None:
    click.echo(json.dumps({'settings': dataclasses.asdict(settings), 'node_name': node_name}))


def test_bind_fills_the_dataclass_from_the_options_named_as_its_fields() -> None:
    runner = CliRunner()
    assert runner.invoke(configure, ['--help']).exit_code == 0
    assert loads == []  # the class is loaded when the verb runs, not for its help
    given = runner.invoke(configure, ['x', '--topics', '/a', '/b', '--rate', '2.5'])
    assert json.loads(given.output) == {
        'settings': {'name': 'x', 'topics': ['/a', '/b'], 'rate': 2.5, 'quiet': False},
        'node_name': 'n',
    }
    # an option not given is handed over as click has it; a field with no option keeps its
    # default
    plain = json.loads(runner.invoke(configure, ['y']).output)
    assert plain['settings'] == {'name': 'y', 'topics': [], 'rate': None, 'quiet': False}
    assert loads == [Settings, Settings]


def test_bind_gives_bag_play_the_library_options(monkeypatch: Any) -> None:
    seen: list[PlayOptions] = []

    def player(*args: Any, **kwargs: Any) -> Any:
        seen.append(args[5](None))  # the verb's options(node), before names are resolved
        raise click.exceptions.Exit(0)

    monkeypatch.setattr('ros2lite.cli.bag.play.bag_player', player)
    monkeypatch.setattr('ros2lite.cli.bag.play.bag_names', lambda node, names: list(names))
    args = ['b', '-r', '2', '-l', '--topics', '/t', '-x', 'z', '--clock', '-d', '1', '-p']
    assert CliRunner().invoke(bag_play, args).exit_code == 0
    assert seen == [
        PlayOptions(
            rate=2.0,
            loop=True,
            topics=['/t'],
            exclude_regex='z',
            delay=1.0,
            clock_hz=40.0,
            start_paused=True,
        )
    ]
