"""ros2lite's commands parse as ros2cli's argparse does where hands and scripts rely on it
(cli/parsing.py): many-valued options stop at the next option, long options may be
abbreviated, negative numbers are values, options may follow positionals, `--` ends the
options, usage errors exit 2."""

from __future__ import annotations

from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import click
import pytest

from ros2lite.cli import parsing
from ros2lite.cli.main import cli as root
from tests.cli.conftest import Result


def params(command: click.Command, *args: str) -> dict[str, Any]:
    """What `command` (a real verb) makes of `args`: parsing only, nothing is run."""
    with command.make_context(command.name or 'verb', list(args)) as ctx:
        return dict(ctx.params)


def test_many_values_stop_at_the_next_option(
    run: Callable[..., Result], tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # the command line of ROS's own Python tutorial
    monkeypatch.chdir(tmp_path)
    created = run(
        'pkg', 'create', '--build-type', 'ament_python',
        '--dependencies', 'rclpy', 'std_msgs', '--node-name', 'my_node', 'py_pubsub',
    )  # fmt: skip
    assert created.code == 0, created.err
    package_xml = (tmp_path / 'py_pubsub' / 'package.xml').read_text()
    assert '<name>py_pubsub</name>' in package_xml
    assert '<depend>rclpy</depend>\n  <depend>std_msgs</depend>' in package_xml
    setup_py = (tmp_path / 'py_pubsub' / 'setup.py').read_text()
    assert "'my_node = py_pubsub.my_node:main'" in setup_py
    # `--` ends the values as it ends the options
    created = run('pkg', 'create', '--dependencies', 'rclpy', '--', 'other')
    assert created.code == 0, created.err
    assert '<depend>rclpy</depend>' in (tmp_path / 'other' / 'package.xml').read_text()
    # at least one value
    missing = run('pkg', 'create', 'third', '--dependencies')
    assert missing.code == 2
    assert "Option '--dependencies' requires at least one argument." in missing.err
    assert not (tmp_path / 'third').exists()


def test_many_values_in_bag_and_security_verbs() -> None:
    from ros2lite.cli.bag.convert import cli as convert
    from ros2lite.cli.bag.record import cli as record
    from ros2lite.cli.param.list import cli as param_list
    from ros2lite.cli.security.generate_artifacts import cli as generate

    got = params(record, '--topics', '/a', '/b', '-o', 'out', '/c', '--exclude-topics', '/d')
    assert got['topics'] == ('/a', '/b')
    assert (got['output'], got['positional_topics']) == ('out', ('/c',))
    assert got['exclude_topics'] == ('/d',)
    # a value given with `=` is the only one, as argparse reads it
    got = params(record, '--topics=/a', '/b')
    assert (got['topics'], got['positional_topics']) == (('/a',), ('/b',))
    got = params(convert, '-i', 'a', 'mcap', '-i', 'b', '-o', 'out.yaml')
    assert got['inputs'] == (('a', 'mcap'), ('b',))
    got = params(param_list, '--param-prefixes', 'a', 'b', '--param-type', '/node')
    assert (got['param_prefixes'], got['param_type'], got['node_name']) == (
        ('a', 'b'),
        True,
        '/node',
    )
    # nargs='*': none at all is fine
    got = params(generate, '-e', '-p', 'x.xml')
    assert (got['enclaves'], [str(p) for p in got['policy_files']]) == ((), ['x.xml'])


def test_unambiguous_prefixes_of_long_options(run: Callable[..., Result]) -> None:
    from ros2lite.cli.doctor import cli as doctor
    from ros2lite.cli.launch import cli as launch

    assert params(doctor, '--include-warning')['include_warnings'] is True
    # two spellings of one option are no ambiguity
    assert params(launch, '--pri', 'pkg', 'a.launch.py')['print_description'] is True
    helped = run('topic', 'pub', '--he')
    assert helped.code == 0 and helped.out.startswith('Usage: ros2lite topic pub')
    ambiguous = run('topic', 'echo', '--qos', 'x', '/t')
    assert ambiguous.code == 2
    assert 'ambiguous option: --qos could match --qos-profile, --qos-depth, ' in ambiguous.err


def test_negative_numbers_are_values(run: Callable[..., Result]) -> None:
    from ros2lite.cli.param.set import cli as param_set
    from ros2lite.cli.topic.pub import cli as pub

    got = params(param_set, '/node', 'a', '-5', 'b', '-1.5', 'c', '-.5', 'd', '-1e-3')
    assert got['params_and_values'] == ('a', '-5', 'b', '-1.5', 'c', '-.5', 'd', '-1e-3')
    # ... unless the command has an option spelled like one (`topic pub -1`), as in argparse
    assert params(pub, '/t', 'std_msgs/msg/String', '-1')['once'] is True
    refused = run('topic', 'pub', '-r', '-1', '/t', 'std_msgs/msg/String')
    assert refused.code == 2 and "Option '-r' requires an argument." in refused.err
    # other words starting with '-' are options, so never an option's value; `--` helps
    refused = run('bag', 'record', '-o', '--all')
    assert refused.code == 2 and "Option '-o' requires an argument." in refused.err
    unknown = run('param', 'set', '/node', 'a', '-x')
    assert unknown.code == 2 and 'No such option' in unknown.err and '-x' in unknown.err
    assert params(param_set, '/node', 'a', '--', '-x')['params_and_values'][-1] == '-x'


@pytest.fixture
def scratch_node(ros_router: str) -> Iterator[str]:
    from tests.cli.param.conftest import start_target, stop

    proc = start_target('param_parsing')
    try:
        yield '/cli/param_parsing'
    finally:
        stop(proc)


def test_param_set_negative_on_a_live_node(run: Callable[..., Result], scratch_node: str) -> None:
    done = run('param', 'set', scratch_node, 'loose', '-5')
    assert (done.code, done.out, done.err) == (0, 'Set parameter successful\n', '')
    assert run('param', 'get', scratch_node, 'loose').out == 'Integer value is: -5\n'


def test_options_follow_positionals() -> None:
    from ros2lite.cli.pkg.create import cli as create
    from ros2lite.cli.topic.echo import cli as echo

    got = params(create, 'name', '--build-type', 'ament_python', '--dependencies', 'a')
    assert (got['package_name'], got['build_type'], got['dependencies']) == (
        'name',
        'ament_python',
        ('a',),
    )
    got = params(echo, '/t', '--once', 'std_msgs/msg/String', '--no-arr')
    assert (got['topic_name'], got['once'], got['no_arr']) == ('/t', True, True)


def test_positionals_are_dealt_as_click_deals_them() -> None:
    """Words that are no option go to the arguments in turn, one with nargs=-1 taking what
    the ones after it leave, exactly as a plain click command deals them."""

    def declare(cls: type[click.Command]) -> click.Command:
        @click.argument('first', required=False)
        @click.argument('middle', nargs=-1)
        @click.argument('pair', nargs=2, required=False)
        @click.argument('last', required=False)
        def deal(**_values: Any) -> None:
            """A probe."""

        return click.command('deal', cls=cls)(deal)

    ours, plain = declare(parsing.Command), declare(click.Command)
    for n in range(7):
        words = [f'w{i}' for i in range(n)]
        outcomes = []
        for command in (ours, plain):
            try:
                outcomes.append(params(command, *words))
            except click.UsageError as e:
                outcomes.append({'error': e.format_message()})
        assert outcomes[0] == outcomes[1], words
        if n == 3:  # the pair is short of a word
            assert outcomes[0] == {'error': "Argument 'pair' takes 2 values."}
    assert params(ours, *'abcdef') == {
        'first': 'a',
        'middle': ('b', 'c'),
        'pair': ('d', 'e'),
        'last': 'f',
    }


def _commands() -> Iterator[tuple[str, click.Command]]:
    """Every command and verb reachable from the root, lazy tables included."""
    ctx = click.Context(root)
    todo: list[tuple[str, click.Command]] = [('ros2lite', root)]
    while todo:
        path, command = todo.pop()
        yield path, command
        if isinstance(command, click.Group):
            for name in command.list_commands(ctx):
                sub = command.get_command(ctx, name)
                assert sub is not None, f'{path} {name}'
                todo.append((f'{path} {name}', sub))


def test_every_command_uses_the_shared_classes() -> None:
    paths = []
    for path, command in _commands():
        paths.append(path)
        shared = parsing.Group if isinstance(command, click.Group) else parsing.Command
        assert isinstance(command, shared), f'{path} is a {type(command).__name__}'
    assert {'ros2lite pkg create', 'ros2lite bag record', 'ros2lite run'} <= set(paths)


def test_use_python_default_buffering(run: Callable[..., Result]) -> None:
    """ros2cli's root flag: stdout keeps Python's buffering instead of a flush per line."""
    import sys

    assert not sys.stdout.line_buffering  # pytest's capture starts block-buffered
    assert run('--use-python-default-buffering', 'extension_points').code == 0
    assert not sys.stdout.line_buffering
    assert run('extension_points').code == 0
    assert sys.stdout.line_buffering
