"""Global CLI behaviour: fast help, exit codes, one-line errors."""

from __future__ import annotations

import os
import subprocess
import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest

from .conftest import Result, run_process


def test_help_imports_nothing_heavy() -> None:
    code = (
        'import sys\nfrom ros2lite.cli.main import main\n'
        'import contextlib, io\n'
        'with contextlib.redirect_stdout(io.StringIO()): main(["--help"])\n'
        'heavy = [m for m in ("zenoh", "yaml", "mcap", "rich", "ros2lite.interfaces") '
        'if m in sys.modules]\nprint(heavy)'
    )
    out = subprocess.run(
        [sys.executable, '-c', code], capture_output=True, text=True, check=True
    ).stdout
    assert out.strip() == '[]'


def test_help_lists_commands() -> None:
    result = run_process('--help')
    assert result.code == 0
    assert 'interface' in result.out and 'Show information about ROS interfaces' in result.out


def test_unknown_command_is_usage_error() -> None:
    result = run_process('frobnicate')
    assert result.code == 2 and 'No such command' in result.err


def test_errors_are_one_line_without_traceback_unless_debug() -> None:
    result = run_process('interface', 'show', 'nope/msg/X')
    assert result.code == 1
    assert result.err == "Unknown package 'nope'\n"
    debug = run_process('--debug', 'interface', 'show', 'nope/msg/X')
    assert debug.code == 1 and 'Traceback' in debug.err
    env_debug = run_process('interface', 'show', 'nope/msg/X', env={'ROS2LITE_DEBUG': '1'})
    assert 'Traceback' in env_debug.err


def test_a_bug_is_said_to_be_one(
    run: Callable[..., Result], monkeypatch: pytest.MonkeyPatch
) -> None:
    """An exception nobody raised on purpose is an internal error, in one line that names
    it; --debug lets its traceback out. The machine refusing (an OSError) is said as is."""
    import ros2lite.cli.interface.packages as verb

    def broken() -> list[str]:
        return {}['no such key']  # type: ignore[no-any-return]

    monkeypatch.setenv('ROS2LITE_DEBUG', '')  # restored after the --debug run sets it
    monkeypatch.setattr(verb, 'list_interfaces', broken)
    failed = run('interface', 'packages')
    assert (failed.code, failed.out) == (1, '')
    assert failed.err == (
        "ros2lite: internal error: KeyError: 'no such key' (run with --debug for the traceback)\n"
    )
    with pytest.raises(KeyError):  # the entry point lets Python print its traceback
        run('--debug', 'interface', 'packages')
    monkeypatch.setenv('ROS2LITE_DEBUG', '')

    def refused() -> list[str]:
        raise PermissionError(13, 'Permission denied', '/opt/ros')

    monkeypatch.setattr(verb, 'list_interfaces', refused)
    failed = run('interface', 'packages')
    assert (failed.code, failed.err) == (1, "[Errno 13] Permission denied: '/opt/ros'\n")


def test_an_internal_error_shows_its_traceback_with_debug(tmp_path: Path) -> None:
    """Through the real entry point: one line, and the traceback with --debug."""
    probe = tmp_path / 'sitecustomize.py'
    probe.write_text(
        'import ros2lite.cli.interface.packages as verb\n'
        'def broken():\n    return 1 / 0\n'
        'verb.list_interfaces = broken\n'
    )
    env = {'PYTHONPATH': os.pathsep.join([str(tmp_path), *sys.path])}
    plain = run_process('interface', 'packages', env=env)
    assert plain.code == 1
    assert plain.err == (
        'ros2lite: internal error: ZeroDivisionError: division by zero '
        '(run with --debug for the traceback)\n'
    )
    debug = run_process('--debug', 'interface', 'packages', env=env)
    assert debug.code == 1
    assert 'Traceback' in debug.err and debug.err.endswith('ZeroDivisionError: division by zero\n')


def test_broken_definition_is_one_line(tmp_path: object) -> None:
    from pathlib import Path

    root = Path(str(tmp_path))
    (root / 'bad_pkg' / 'msg').mkdir(parents=True)
    (root / 'bad_pkg' / 'msg' / 'Bad.msg').write_text('int32 ok\nint33 broken\n')
    result = run_process(
        'interface', 'hash', 'bad_pkg/msg/Bad', env={'ROS2LITE_INTERFACE_PATH': str(root)}
    )
    assert result.code == 1
    assert result.err.count('\n') == 1
    assert 'Bad.msg:2:' in result.err and "invalid type name 'int33'" in result.err


def test_sigterm_leaves_with_status_15(processes: Any, ros_context: Any) -> None:
    """ros2cli turns SIGTERM (rclpy's ExternalShutdownException) into status 15."""
    import signal

    from ros2lite.graph import snapshot
    from tests.spinning import wait_until

    proc = processes.cli('topic', 'echo', '/sigterm_topic', 'std_msgs/msg/String')
    # once echo's subscription is in the graph, it is past start-up
    wait_until(
        lambda: any(
            e.topic_name == '/sigterm_topic'
            for e in snapshot(ros_context.session, ros_context.domain_id)
        ),
        timeout=15,
    )
    proc.send_signal(signal.SIGTERM)
    _out, err = proc.communicate(timeout=10)
    assert proc.returncode == 15
    assert 'Traceback' not in err


@pytest.mark.parametrize(
    'verb',
    [
        ['topic', 'echo', '/sigint_topic', 'std_msgs/msg/String'],
        ['topic', 'hz', '/sigint_topic'],
        ['topic', 'bw', '/sigint_topic'],
        ['topic', 'delay', '/sigint_topic'],
        ['topic', 'pub', '/sigint_topic', 'std_msgs/msg/String'],
    ],
    ids=lambda v: v[1],
)
def test_ctrl_c_leaves_with_status_2(processes: Any, ros_context: Any, verb: list[str]) -> None:
    """ros2cli's KeyboardInterrupt status, in every verb that runs until interrupted."""
    import signal

    from ros2lite.graph import snapshot
    from tests.spinning import wait_until

    proc = processes.cli(*verb)
    hidden = f'_ros2lite_{proc.pid}'
    # once the verb's hidden node is in the graph, it is past start-up
    wait_until(
        lambda: any(
            e.node_name == hidden for e in snapshot(ros_context.session, ros_context.domain_id)
        ),
        timeout=15,
    )
    proc.send_signal(signal.SIGINT)
    _out, err = proc.communicate(timeout=10)
    assert (proc.returncode, err) == (2, '')


@pytest.mark.parametrize(
    ('raised', 'status'), [('KeyboardInterrupt', 2), ('Terminated', 15)], ids=['int', 'term']
)
def test_an_interrupt_wrapped_by_python_is_still_an_interrupt(
    raised: str, status: int, capsys: pytest.CaptureFixture[str]
) -> None:
    """Python 3.11 turns an exception inside `__set_name__` (class creation during a lazy
    import) into RuntimeError; a Ctrl-C landing there must not become an error message."""
    import click

    from ros2lite.cli import main as cli_main
    from ros2lite.util.process import Terminated

    kind = {'KeyboardInterrupt': KeyboardInterrupt, 'Terminated': Terminated}[raised]

    class Descriptor:
        def __set_name__(self, owner: type, name: str) -> None:
            raise kind()

    @click.command('interrupted-in-import')
    def verb() -> None:
        try:
            type('Late', (), {'field': Descriptor()})
        except BaseException as e:  # what 3.11 does; 3.12 lets the interrupt through as is
            if isinstance(e, kind):
                raise RuntimeError("Error calling __set_name__ on 'Descriptor'") from e
            raise

    cli_main.cli.add_command(verb)
    try:
        assert cli_main._main(['interrupted-in-import']) == status
    finally:
        cli_main.cli.commands.pop('interrupted-in-import')
    assert capsys.readouterr().err == ''
