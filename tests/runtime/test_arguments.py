"""`--ros-args` parsing: what rcl accepts, what it rejects, and how blocks and files combine."""

from __future__ import annotations

from pathlib import Path

import pytest

from ros2lite.parameters.node_api import load_params_file, node_overrides
from ros2lite.runtime.arguments import (
    Remap,
    RosArgs,
    RosArgsError,
    parse_ros_args,
    split_ros_args,
)


def test_split_keeps_user_arguments() -> None:
    user, blocks = split_ros_args(
        ['a', '--ros-args', '-r', 'x:=y', '--', 'b', '--ros-args', '-p', 'p:=1']
    )
    assert user == ['a', 'b']
    assert blocks == [['-r', 'x:=y'], ['-p', 'p:=1']]
    assert split_ros_args(['only', 'user']) == (['only', 'user'], [])
    # a block runs to the end when not closed by `--`
    assert split_ros_args(['--ros-args', '-r', 'a:=b', 'c']) == ([], [['-r', 'a:=b', 'c']])


def test_remaps_and_special_names() -> None:
    args = parse_ros_args(
        [
            'prog',
            '--ros-args',
            '-r',
            'chatter:=/other',
            '--remap',
            'talker:__node:=t2',
            '-r',
            '__ns:=/ns',
        ]
    )
    assert args.remaps == [
        Remap(None, 'chatter', '/other'),
        Remap('talker', '__node', 't2'),
        Remap(None, '__ns', '/ns'),
    ]
    assert args.node_name_override('talker') == 't2'
    assert args.node_name_override('listener') is None
    assert args.namespace_override('anyone') == '/ns'


def test_last_special_rule_wins() -> None:
    args = parse_ros_args(['--ros-args', '-r', '__node:=a', '-r', '__node:=b'])
    assert args.node_name_override('n') == 'b'


def test_parameters_are_yaml_typed() -> None:
    args = parse_ros_args(
        [
            '--ros-args',
            '-p',
            'i:=3',
            '-p',
            'f:=2.5',
            '-p',
            'b:=true',
            '-p',
            's:=hello',
            '-p',
            'l:=[1, 2]',
            '-p',
            'q:="3"',
            '--param',
            'node:x:=1',
            '-p',
            'e:=',
        ]
    )
    assert args.params[None] == {
        'i': 3,
        'f': 2.5,
        'b': True,
        's': 'hello',
        'l': [1, 2],
        'q': '3',
        'e': None,
    }
    assert args.params['node'] == {'x': 1}
    assert node_overrides(args, '/node', 'node')['x'] == 1
    assert 'x' not in node_overrides(args, '/other', 'other')


def test_log_levels_and_enclave() -> None:
    args = parse_ros_args(
        [
            '--ros-args',
            '--log-level',
            'debug',
            '--log-level',
            'talker:=WARN',
            '-e',
            '/secure',
            '--disable-rosout-logs',
        ]
    )
    assert args.log_levels == {None: 10, 'talker': 30}
    assert args.enclave == '/secure'


@pytest.mark.parametrize(
    'argv, message',
    [
        (['--ros-args', '-r'], "needs a value"),
        (['--ros-args', '-r', 'no_assignment'], "remap rule"),
        (['--ros-args', '-r', ':=x'], "remap rule"),
        (['--ros-args', '-p', 'novalue'], "parameter rule"),
        (['--ros-args', '--log-level', 'loud'], "Invalid log level"),
        (['--ros-args', '--bogus'], "Unknown ROS argument '--bogus'"),
        (['--ros-args', '--params-file', '/does/not/exist.yaml'], "parameters file"),
    ],
)
def test_errors_say_what_is_wrong(argv: list[str], message: str) -> None:
    with pytest.raises(RosArgsError, match=message):
        parse_ros_args(argv)


def test_merge_prefers_local() -> None:
    glob = parse_ros_args(
        ['--ros-args', '-r', '__ns:=/g', '-p', 'a:=1', '-p', 'b:=1', '--log-level', 'info']
    )
    local = parse_ros_args(['--ros-args', '-r', '__ns:=/l', '-p', 'a:=2', '--log-level', 'debug'])
    merged = glob.merge(local)
    assert merged.namespace_override('n') == '/l'
    assert merged.params[None] == {'a': 2, 'b': 1}
    assert merged.log_levels[None] == 10
    assert RosArgs().merge(RosArgs()) == RosArgs()


def test_params_file_matching(tmp_path: Path) -> None:
    path = tmp_path / 'p.yaml'
    path.write_text(
        '/**:\n  ros__parameters:\n    everyone: 1\n    shared: all\n'
        '/robot1/talker:\n  ros__parameters:\n    shared: mine\n    deep:\n      a: 1\n'
        'listener:\n  ros__parameters:\n    only_listener: true\n'
        '/*/talker:\n  ros__parameters:\n    wild: yes\n'
    )
    talker = load_params_file(path, '/robot1/talker', 'talker')
    assert talker == {'everyone': 1, 'shared': 'mine', 'deep.a': 1, 'wild': True}
    assert load_params_file(path, '/listener', 'listener') == {
        'everyone': 1,
        'shared': 'all',
        'only_listener': True,
    }
    args = parse_ros_args(['--ros-args', '--params-file', str(path), '-p', 'shared:=cli'])
    assert node_overrides(args, '/robot1/talker', 'talker')['shared'] == 'cli'


def test_params_file_errors(tmp_path: Path) -> None:
    bad = tmp_path / 'bad.yaml'
    bad.write_text('- just\n- a list\n')
    with pytest.raises(RosArgsError, match='must map node names'):
        load_params_file(bad, '/n', 'n')
    missing = tmp_path / 'missing_section.yaml'
    missing.write_text('n:\n  ros__parameters: 3\n')
    with pytest.raises(RosArgsError, match='ros__parameters'):
        load_params_file(missing, '/n', 'n')
    broken = tmp_path / 'broken.yaml'
    broken.write_text('a: [unclosed\n')
    with pytest.raises(RosArgsError, match="Couldn't read"):
        load_params_file(broken, '/n', 'n')


def test_later_rules_win_over_earlier_files_and_back(tmp_path: Path) -> None:
    """-p rules and params files count in the order given, as in rcl."""
    path = tmp_path / 'p.yaml'
    path.write_text('/**:\n  ros__parameters:\n    a: file\n    b: file\n')
    args = parse_ros_args(
        ['--ros-args', '-p', 'a:=early', '--params-file', str(path), '-p', 'b:=late']
    )
    assert node_overrides(args, '/n', 'n') == {'a': 'file', 'b': 'late'}
    flags = parse_ros_args(['--ros-args', '--disable-rosout-logs', '--enable-stdout-logs'])
    assert (flags.rosout_logs, flags.stdout_logs) == (False, True)
