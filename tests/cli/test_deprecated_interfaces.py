"""`msg` and `srv`: ros2cli's deprecation line on stderr, ros2msg/ros2srv's output."""

from __future__ import annotations

from collections.abc import Callable

from tests.cli.conftest import Result

Run = Callable[..., Result]


def deprecation(kind: str, instead: str) -> str:
    return (
        f"'ros2 {kind}' is deprecated and will be removed in a future ROS release. "
        f"Instead use: 'ros2 interface {instead}'\n"
    )


def test_msg(run: Run) -> None:
    listed = run('msg', 'list')
    assert listed.err == deprecation('msg', 'list -m')
    lines = listed.out.splitlines()
    assert 'std_msgs/msg/String' in lines and all('/msg/' in line for line in lines)
    assert lines == sorted(lines)
    package = run('msg', 'package', 'std_srvs')
    assert (package.out, package.err) == ('', deprecation('msg', 'package std_srvs'))
    assert run('msg', 'package', 'std_msgs').out.splitlines()[:2] == [
        'std_msgs/msg/Bool',
        'std_msgs/msg/Byte',
    ]
    assert 'std_msgs' in run('msg', 'packages').out.splitlines()
    assert 'std_srvs' not in run('msg', 'packages').out.splitlines()
    shown = run('msg', 'show', 'std_msgs/String')
    assert shown.err == deprecation('msg', 'show std_msgs/msg/String')
    assert 'string data' in shown.out.splitlines()


def test_srv(run: Run) -> None:
    assert run('srv', 'list').err == deprecation('srv', 'list -s')
    assert 'std_srvs/srv/Trigger' in run('srv', 'package', 'std_srvs').out.splitlines()
    shown = run('srv', 'show', 'std_srvs/srv/SetBool')
    assert shown.err == deprecation('srv', 'show std_srvs/srv/SetBool.srv')
    assert '---' in shown.out.splitlines() and 'bool data' in shown.out


def test_errors(run: Run) -> None:
    for args, message in (
        (('msg', 'package', 'not_a_package'), 'Unknown package name'),
        (('msg', 'show', 'std_msgs/msg/NotAMessage'), 'Unknown message name'),
        (('msg', 'show', 'not_a_package/msg/String'), 'Unknown package name'),
        (('msg', 'show', 'not_a_message_type'), 'The passed message type is invalid'),
        (('srv', 'show', 'std_srvs/Nope'), 'Unknown service name'),
    ):
        result = run(*args)
        assert result.code == 1 and result.err.splitlines()[-1] == message, args
